"""Fixed-step classical RK4 at the sample step, inputs held over each step (SPEC section 3).

Three backends, same scheme and equations (the tests check they agree):

- ``numba`` (default): compiled, samples outer and scenarios inner, each RK4 stage a few loops over
  the scenarios that LLVM vectorises (SIMD); |v|^n1 by a vectorisable polynomial exp/log;
- ``numba-scalar``: compiled, scenarios outer, samples inner, the state in registers, calling
  :func:`drivetrain.plant_derivatives_scalar` (libm exp/log);
- ``numpy``: the step vectorised over the scenarios with numpy calls (:func:`drivetrain.plant_derivatives`).

Per step k (state x_k at t_k = k*h, held load L_k, supply u evaluated at t_k, t_k+h/2, t_k+h):
    k1 = f(x_k, u(t_k)), k2 = f(x_k + h/2 k1, u(t_k+h/2)), k3 = f(x_k + h/2 k2, u(t_k+h/2)),
    k4 = f(x_k + h k3, u(t_k+h)),  x_{k+1} = x_k + h/6 (k1 + 2 k2 + 2 k3 + k4).
The recorded sample k holds x_k and the exact derivatives k1 (a1 = r*Omega_mb*dw1/dt, a2 = x'').

Zone crossings: when |Delta| - beta changes sign over a step, the step is redone by
:func:`crossing_step` (crossing located on the Hermite interpolant of Delta, RK4 to it and from it),
because the clutch's damper engages with a jump in torque there.
"""
from __future__ import annotations

import numpy as np

import math

from ._numba import HAVE_NUMBA, jitable, numba
from .drivetrain import (N_STATES, P_DC, P_F0, P_J2, P_K, P_KC, P_M, P_ON_ABSORBER, P_ON_CLUTCH, P_ON_RESISTANCE,
                         P_ON_SPRING, P_OMEGA_B, P_OMEGA_MB, P_R, P_RR, P_RS, P_TB, P_TM, P_W, P_XM, P_XR, P_XS, S_ALPHA1, S_ALPHA2, S_DELTA, S_OMEGA2, S_PRA, S_PRB, S_PSA,
                         S_PSB, S_W1, S_XDOT, S_Z, plant_derivatives,
                         plant_derivatives_scalar)

# recorded outputs, first axis of the output block
OUTPUT_NAMES = ("a1", "a2", "omega1", "omega2", "angle_difference", "alpha1", "alpha2", "transmitted_torque_Nm")
N_OUTPUTS = len(OUTPUT_NAMES)


@jitable
def _derivs_at(y, tau, phase, u_amp, ld, bs, cs, ns, p, mode, out):
    ph = phase + p[P_OMEGA_B] * tau
    der, aux = plant_derivatives_scalar(y[0], y[1], y[2], y[3], y[4], y[5], y[8], y[9], y[10],
                                        u_amp * math.cos(ph), u_amp * math.sin(ph), ld, bs, cs, ns, p, mode)
    for i in range(11):
        out[i] = der[i]


@jitable
def _rk4_substep(y, hs, tau0, phase, u_amp, ld, bs, cs, ns, p, mode):
    """One classical RK4 step of length hs from y (in place), starting tau0 after the sample instant."""
    k1 = np.empty(11)
    k2 = np.empty(11)
    k3 = np.empty(11)
    k4 = np.empty(11)
    tmp = np.empty(11)
    _derivs_at(y, tau0, phase, u_amp, ld, bs, cs, ns, p, mode, k1)
    for i in range(11):
        tmp[i] = y[i] + 0.5 * hs * k1[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, bs, cs, ns, p, mode, k2)
    for i in range(11):
        tmp[i] = y[i] + 0.5 * hs * k2[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, bs, cs, ns, p, mode, k3)
    for i in range(11):
        tmp[i] = y[i] + hs * k3[i]
    _derivs_at(tmp, tau0 + hs, phase, u_amp, ld, bs, cs, ns, p, mode, k4)
    for i in range(11):
        y[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@jitable
def crossing_step(y0, y1, h, phase, u_amp, ld, bs, cs, ns, p):
    """Redo a step in which Delta crossed the zone boundary |Delta| = beta (the clutch's damper engages
    with a jump there, which costs a plain RK4 step O(h) accuracy): locate the crossing on the cubic
    Hermite interpolant of Delta (slopes Omega1 - Omega2 at both ends), then RK4 up to it with the
    start side's law and on from it with the other side's. y0: state at the step start; y1: the plain
    step's result, overwritten with the located one. Returns the crossing's fraction of the step."""
    omb = p[P_OMEGA_MB]
    d0, d1 = y0[5], y1[5]
    r0 = (y0[4] * omb - y0[8]) * h
    r1 = (y1[4] * omb - y1[8]) * h
    inside0 = abs(d0) < bs
    sgn = (1.0 if d1 > 0.0 else -1.0) if inside0 else (1.0 if d0 > 0.0 else -1.0)
    target = sgn * bs
    lo, hi = 0.0, 1.0
    f_lo = d0 - target
    for _ in range(60):
        th = 0.5 * (lo + hi)
        t2 = th * th
        t3 = t2 * th
        val = ((2 * t3 - 3 * t2 + 1) * d0 + (t3 - 2 * t2 + th) * r0 + (-2 * t3 + 3 * t2) * d1
               + (t3 - t2) * r1) - target
        if (val > 0.0) == (f_lo > 0.0):
            lo = th
            f_lo = val
        else:
            hi = th
    th = 0.5 * (lo + hi)
    mode0 = 2 if inside0 else 1
    mode1 = 1 if inside0 else 2
    for i in range(11):
        y1[i] = y0[i]
    if th > 0.0:
        _rk4_substep(y1, th * h, 0.0, phase, u_amp, ld, bs, cs, ns, p, mode0)
    if th < 1.0:
        _rk4_substep(y1, (1.0 - th) * h, th * h, phase, u_amp, ld, bs, cs, ns, p, mode1)
    return th


def _rk4_loop(x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, out, states, record_states):
    n_scen = x.shape[0]
    n = load.shape[1]
    r = p[P_R]
    omega_mb = p[P_OMEGA_MB]
    clutch_on = p[P_ON_CLUTCH] != 0.0
    y0 = np.empty(11)
    y1 = np.empty(11)
    for s in range(n_scen):
        psa = x[s, 0]; psb = x[s, 1]; pra = x[s, 2]; prb = x[s, 3]; w1 = x[s, 4]; d = x[s, 5]
        al1 = x[s, 6]; al2 = x[s, 7]; o2 = x[s, 8]; z = x[s, 9]; xd = x[s, 10]
        bs = beta[s]; cs = c[s]; ns = n1[s]
        for k in range(n):
            ld = load[s, k]
            if record_states:
                states[0, s, k] = psa; states[1, s, k] = psb; states[2, s, k] = pra; states[3, s, k] = prb
                states[4, s, k] = w1; states[5, s, k] = d; states[6, s, k] = al1; states[7, s, k] = al2
                states[8, s, k] = o2; states[9, s, k] = z; states[10, s, k] = xd
            f1, aux = plant_derivatives_scalar(psa, psb, pra, prb, w1, d, o2, z, xd, ua[k, 0], ub[k, 0], ld, bs, cs, ns, p)
            out[0, s, k] = r * omega_mb * f1[4]
            out[1, s, k] = f1[10]
            out[2, s, k] = w1 * omega_mb
            out[3, s, k] = o2
            out[4, s, k] = d
            out[5, s, k] = al1
            out[6, s, k] = al2
            out[7, s, k] = aux[1]
            hh = 0.5 * h
            f2, aux = plant_derivatives_scalar(psa + hh * f1[0], psb + hh * f1[1], pra + hh * f1[2], prb + hh * f1[3],
                                        w1 + hh * f1[4], d + hh * f1[5], o2 + hh * f1[8], z + hh * f1[9],
                                        xd + hh * f1[10], ua[k, 1], ub[k, 1], ld, bs, cs, ns, p)
            f3, aux = plant_derivatives_scalar(psa + hh * f2[0], psb + hh * f2[1], pra + hh * f2[2], prb + hh * f2[3],
                                        w1 + hh * f2[4], d + hh * f2[5], o2 + hh * f2[8], z + hh * f2[9],
                                        xd + hh * f2[10], ua[k, 1], ub[k, 1], ld, bs, cs, ns, p)
            f4, aux = plant_derivatives_scalar(psa + h * f3[0], psb + h * f3[1], pra + h * f3[2], prb + h * f3[3],
                                        w1 + h * f3[4], d + h * f3[5], o2 + h * f3[8], z + h * f3[9],
                                        xd + h * f3[10], ua[k, 2], ub[k, 2], ld, bs, cs, ns, p)
            h6 = h / 6.0
            psa_new = psa + h6 * (f1[0] + 2.0 * f2[0] + 2.0 * f3[0] + f4[0])
            psb_new = psb + h6 * (f1[1] + 2.0 * f2[1] + 2.0 * f3[1] + f4[1])
            pra_new = pra + h6 * (f1[2] + 2.0 * f2[2] + 2.0 * f3[2] + f4[2])
            prb_new = prb + h6 * (f1[3] + 2.0 * f2[3] + 2.0 * f3[3] + f4[3])
            w1_new = w1 + h6 * (f1[4] + 2.0 * f2[4] + 2.0 * f3[4] + f4[4])
            d_new = d + h6 * (f1[5] + 2.0 * f2[5] + 2.0 * f3[5] + f4[5])
            al1_new = al1 + h6 * (f1[6] + 2.0 * f2[6] + 2.0 * f3[6] + f4[6])
            al2_new = al2 + h6 * (f1[7] + 2.0 * f2[7] + 2.0 * f3[7] + f4[7])
            o2_new = o2 + h6 * (f1[8] + 2.0 * f2[8] + 2.0 * f3[8] + f4[8])
            z_new = z + h6 * (f1[9] + 2.0 * f2[9] + 2.0 * f3[9] + f4[9])
            xd_new = xd + h6 * (f1[10] + 2.0 * f2[10] + 2.0 * f3[10] + f4[10])
            if clutch_on and ((abs(d) < bs) != (abs(d_new) < bs)):
                y0[0] = psa; y0[1] = psb; y0[2] = pra; y0[3] = prb; y0[4] = w1; y0[5] = d
                y0[6] = al1; y0[7] = al2; y0[8] = o2; y0[9] = z; y0[10] = xd
                y1[0] = psa_new; y1[1] = psb_new; y1[2] = pra_new; y1[3] = prb_new; y1[4] = w1_new
                y1[5] = d_new; y1[6] = al1_new; y1[7] = al2_new; y1[8] = o2_new; y1[9] = z_new; y1[10] = xd_new
                crossing_step(y0, y1, h, phase[k], u_amp, ld, bs, cs, ns, p)
                psa_new = y1[0]; psb_new = y1[1]; pra_new = y1[2]; prb_new = y1[3]; w1_new = y1[4]
                d_new = y1[5]; al1_new = y1[6]; al2_new = y1[7]; o2_new = y1[8]; z_new = y1[9]; xd_new = y1[10]
            psa = psa_new; psb = psb_new; pra = pra_new; prb = prb_new; w1 = w1_new; d = d_new
            al1 = al1_new; al2 = al2_new; o2 = o2_new; z = z_new; xd = xd_new
        x[s, 0] = psa; x[s, 1] = psb; x[s, 2] = pra; x[s, 3] = prb; x[s, 4] = w1; x[s, 5] = d
        x[s, 6] = al1; x[s, 7] = al2; x[s, 8] = o2; x[s, 9] = z; x[s, 10] = xd



# --- SIMD kernel: all scenarios advanced together, the loops over scenarios vectorise (AVX2/AVX-512) ---
# |v|^n1 = exp(n1*log|v|) with a polynomial log/exp (bit-level exponent split through int64 views of
# float arrays), because numba's LLVM has no vector exp/log. Relative error < 1e-13 (test_plant_integrator).
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_INV_LN2 = 1.44269504088896338700e+00
_SQRT2 = 1.4142135623730951
_MANT = np.int64(0x000FFFFFFFFFFFFF)
_ONE_BITS = np.int64(0x3FF0000000000000)
_OUT_BLOCK = 32
_LANES = 8    # pad the scenario axis to whole AVX-512 vectors of doubles


def _stage_simd(Y, K, ua, ub, load, beta, c, n1, p, TC, AV, AVI, MI, MF, E, G, KI, KF):
    """One RK4 stage for all scenarios: K = f(Y) (both (11, S)), TC = T_c; same equations as
    drivetrain.plant_derivatives, expanded by hand in four vectorisable loops over the scenarios."""
    S = Y.shape[1]
    xs=p[P_XS]; xr=p[P_XR]; xm=p[P_XM]; iw=1.0/p[P_W]; ob=p[P_OMEGA_B]; rs=p[P_RS]; rr=p[P_RR]
    omb=p[P_OMEGA_MB]; kc=p[P_KC]; dc=p[P_DC]; r=p[P_R]; itb=1.0/p[P_TB]; itm=1.0/p[P_TM]; onc=p[P_ON_CLUTCH]
    for s in range(S):
        psa=Y[0,s]; psb=Y[1,s]; pra=Y[2,s]; prb=Y[3,s]; w1=Y[4,s]; d=Y[5,s]; o2=Y[8,s]; xd=Y[10,s]
        isa=(xr*psa-xm*pra)*iw; isb=(xr*psb-xm*prb)*iw; ira=(xs*pra-xm*psa)*iw; irb=(xs*prb-xm*psb)*iw
        K[0,s]=ob*(ua-rs*isa); K[1,s]=ob*(ub-rs*isb); K[2,s]=ob*(-rr*ira-w1*prb); K[3,s]=ob*(-rr*irb+w1*pra)
        te=psa*isb-psb*isa
        o1=w1*omb; rel=o1-o2
        ad=abs(d); sg=1.0 if d>0.0 else -1.0
        raw=kc*(ad-beta[s])+sg*dc*rel
        tc=sg*max(raw,0.0)
        tc=tc if ad>=beta[s] else 0.0
        tc*=onc
        TC[s]=tc
        K[4,s]=(te-tc*itb-load[s])*itm
        K[5,s]=rel; K[6,s]=o1; K[7,s]=o2
        v=r*o2-xd
        K[9,s]=v
        AV[s]=max(abs(v), 1e-290)
    for s in range(S):
        b=AVI[s]
        MI[s]=(b & _MANT) | _ONE_BITS
        E[s]=np.float64((b >> 52) - 1023)
    for s in range(S):
        m=MF[s]; e=E[s]
        big = m > _SQRT2
        m = m*0.5 if big else m
        e = e+1.0 if big else e
        t=(m-1.0)/(m+1.0); t2=t*t
        pl = 2.0*t*(1.0+t2*(1.0/3+t2*(1.0/5+t2*(1.0/7+t2*(1.0/9+t2*(1.0/11+t2*(1.0/13+t2*(1.0/15+t2*(1.0/17)))))))))
        y = n1[s]*(e*_LN2_HI + (e*_LN2_LO + pl))
        kf = math.floor(y*_INV_LN2+0.5)
        kf = max(kf, -1000.0)
        rr_ = (y - kf*_LN2_HI) - kf*_LN2_LO
        ex = 1.0+rr_*(1.0+rr_*(0.5+rr_*(1.0/6+rr_*(1.0/24+rr_*(1.0/120+rr_*(1.0/720+rr_*(1.0/5040+rr_*(1.0/40320+rr_*(1.0/362880+rr_*(1.0/3628800+rr_*(1.0/39916800+rr_*(1.0/479001600))))))))))))
        G[s]=ex
        KI[s]=(np.int64(kf)+1023) << 52
    r_=p[P_R]; k_=p[P_K]*p[P_ON_SPRING]; ona=p[P_ON_ABSORBER]; ij2=1.0/p[P_J2]; im=1.0/p[P_M]; f0=p[P_F0]*p[P_ON_RESISTANCE]
    for s in range(S):
        v=K[9,s]
        pw=G[s]*KF[s]
        fa=c[s]*pw
        fa = fa if v>0.0 else (-fa if v<0.0 else 0.0)
        f=k_*Y[9,s]+ona*fa
        K[8,s]=(TC[s]-r_*f)*ij2
        K[10,s]=(f-f0)*im


def _rk4_simd_loop(x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, out, states, record_states, record_outputs, sel):
    """The RK4 scheme of _rk4_loop with the samples outer and the scenarios inner (vectorised).

    The scenario axis is padded to a multiple of _LANES with copies of the last scenario, so every
    loop over the scenarios runs whole SIMD vectors (no scalar remainder iterations); the padding
    lanes are never written out and never take the crossing step. Without fastmath reassociation or
    contraction every lane computes the same IEEE operations whether in a vector or not, so the
    padding does not change any real scenario's result."""
    S=x.shape[0]; n=load.shape[1]
    Sp=((S+_LANES-1)//_LANES)*_LANES
    Y=np.empty((11,Sp))
    for i in range(11):
        for s in range(Sp):
            Y[i,s]=x[min(s,S-1),i]
    T=np.empty_like(Y)
    K1=np.empty_like(Y); K2=np.empty_like(Y); K3=np.empty_like(Y); K4=np.empty_like(Y)
    TC=np.empty(Sp); AV=np.empty(Sp); AVI=AV.view(np.int64); MI=np.empty(Sp,np.int64); MF=MI.view(np.float64)
    E=np.empty(Sp); G=np.empty(Sp); KI=np.empty(Sp,np.int64); KF=KI.view(np.float64)
    LT=np.empty((n,Sp))
    for k in range(n):
        for s in range(Sp):
            LT[k,s]=load[min(s,S-1),k]
    beta_=np.empty(Sp); c_=np.empty(Sp); n1_=np.empty(Sp)
    for s in range(Sp):
        beta_[s]=beta[min(s,S-1)]; c_[s]=c[min(s,S-1)]; n1_[s]=n1[min(s,S-1)]
    beta=beta_; c=c_; n1=n1_
    r=p[P_R]; omb=p[P_OMEGA_MB]; hh=0.5*h; h6=h/6.0
    y0=np.empty(11); y1=np.empty(11)
    nsel = sel.shape[0]
    buf = np.empty((nsel, _OUT_BLOCK, Sp))
    for k in range(n):
        ld=LT[k]
        _stage_simd_jit(Y,K1,ua[k,0],ub[k,0],ld,beta,c,n1,p,TC,AV,AVI,MI,MF,E,G,KI,KF)
        if record_states:
            for i in range(11):
                for s in range(S):
                    states[i, s, k] = Y[i, s]
        if record_outputs:
            # the requested outputs (sel: indices into OUTPUT_NAMES) go through a (nsel, B, S) buffer,
            # written contiguously per step and flushed to out (nsel, S, n) every B steps (avoids
            # nsel*S scattered stores per step)
            b = k % _OUT_BLOCK
            for j in range(nsel):
                o = sel[j]
                if o == 0:
                    for s in range(Sp): buf[j, b, s] = r * omb * K1[4, s]
                elif o == 1:
                    for s in range(Sp): buf[j, b, s] = K1[10, s]
                elif o == 2:
                    for s in range(Sp): buf[j, b, s] = Y[4, s] * omb
                elif o == 3:
                    for s in range(Sp): buf[j, b, s] = Y[8, s]
                elif o == 4:
                    for s in range(Sp): buf[j, b, s] = Y[5, s]
                elif o == 5:
                    for s in range(Sp): buf[j, b, s] = Y[6, s]
                elif o == 6:
                    for s in range(Sp): buf[j, b, s] = Y[7, s]
                else:
                    for s in range(Sp): buf[j, b, s] = TC[s]
            if b == _OUT_BLOCK - 1 or k == n - 1:
                k_start = k - b
                for j in range(nsel):
                    for s in range(S):
                        for bb in range(b + 1):
                            out[j, s, k_start + bb] = buf[j, bb, s]
        for i in range(11):
            for s in range(Sp): T[i,s]=Y[i,s]+hh*K1[i,s]
        _stage_simd_jit(T,K2,ua[k,1],ub[k,1],ld,beta,c,n1,p,TC,AV,AVI,MI,MF,E,G,KI,KF)
        for i in range(11):
            for s in range(Sp): T[i,s]=Y[i,s]+hh*K2[i,s]
        _stage_simd_jit(T,K3,ua[k,1],ub[k,1],ld,beta,c,n1,p,TC,AV,AVI,MI,MF,E,G,KI,KF)
        for i in range(11):
            for s in range(Sp): T[i,s]=Y[i,s]+h*K3[i,s]
        _stage_simd_jit(T,K4,ua[k,2],ub[k,2],ld,beta,c,n1,p,TC,AV,AVI,MI,MF,E,G,KI,KF)
        for i in range(11):
            for s in range(Sp): T[i,s]=Y[i,s]+h6*(K1[i,s]+2.0*K2[i,s]+2.0*K3[i,s]+K4[i,s])
        if p[P_ON_CLUTCH]!=0.0:
            for s in range(S):
                if (abs(Y[5,s])<beta[s]) != (abs(T[5,s])<beta[s]):
                    for i in range(11):
                        y0[i]=Y[i,s]; y1[i]=T[i,s]
                    crossing_step(y0,y1,h,phase[k],u_amp,ld[s],beta[s],c[s],n1[s],p)
                    for i in range(11): T[i,s]=y1[i]
        Y, T = T, Y
    for s in range(S):
        for i in range(11):
            x[s,i]=Y[i,s]


if HAVE_NUMBA:
    _JIT = dict(cache=True, nogil=True, fastmath=True, error_model="numpy")
    _rk4_numba_scalar = numba.njit(**_JIT)(_rk4_loop)
    _stage_simd_jit = numba.njit(**_JIT)(_stage_simd)
    _rk4_numba_simd = numba.njit(**_JIT)(_rk4_simd_loop)
else:  # pragma: no cover
    _rk4_numba_scalar = _rk4_numba_simd = None
    _stage_simd_jit = _stage_simd


def _rk4_numpy(x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, out, states, record_states):
    """Same scheme, vectorised over the scenarios (the state is advanced in place)."""
    n = load.shape[1]
    r, omega_mb = p[P_R], p[P_OMEGA_MB]
    y = [x[:, i].copy() for i in range(N_STATES)]

    def f(state, ua_, ub_, ld):
        der, aux = plant_derivatives(state[S_PSA], state[S_PSB], state[S_PRA], state[S_PRB], state[S_W1],
                                     state[S_DELTA], state[S_OMEGA2], state[S_Z], state[S_XDOT], ua_, ub_, ld,
                                     beta, c, n1, p)
        return der, aux

    for k in range(n):
        ld = load[:, k]
        if record_states:
            for i in range(N_STATES):
                states[i, :, k] = y[i]
        f1, aux = f(y, ua[k, 0], ub[k, 0], ld)
        out[0, :, k] = r * omega_mb * f1[4]
        out[1, :, k] = f1[10]
        out[2, :, k] = y[S_W1] * omega_mb
        out[3, :, k] = y[S_OMEGA2]
        out[4, :, k] = y[S_DELTA]
        out[5, :, k] = y[S_ALPHA1]
        out[6, :, k] = y[S_ALPHA2]
        out[7, :, k] = aux[1]
        f2, _ = f([y[i] + 0.5 * h * f1[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld)
        f3, _ = f([y[i] + 0.5 * h * f2[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld)
        f4, _ = f([y[i] + h * f3[i] for i in range(N_STATES)], ua[k, 2], ub[k, 2], ld)
        y_new = [y[i] + (h / 6.0) * (f1[i] + 2.0 * f2[i] + 2.0 * f3[i] + f4[i]) for i in range(N_STATES)]
        if p[P_ON_CLUTCH] != 0.0:
            crossed = np.flatnonzero((np.abs(y[S_DELTA]) < beta) != (np.abs(y_new[S_DELTA]) < beta))
            for s in crossed:   # rare: the same located crossing step as the compiled kernel, in Python
                y0 = np.array([y[i][s] for i in range(N_STATES)])
                y1 = np.array([y_new[i][s] for i in range(N_STATES)])
                crossing_step(y0, y1, h, phase[k], u_amp, float(ld[s]), float(beta[s]), float(c[s]), float(n1[s]), p)
                for i in range(N_STATES):
                    y_new[i][s] = y1[i]
        y = y_new
    for i in range(N_STATES):
        x[:, i] = y[i]


BACKENDS = ("auto", "numba", "numba-scalar", "numpy")


def resolve_backend(name: str) -> str:
    """'auto' -> 'numba' when numba is importable, else 'numpy'."""
    if name not in BACKENDS:
        raise ValueError(f"backend {name!r} is not allowed; allowed: " + ", ".join(repr(b) for b in BACKENDS))
    if name == "auto":
        return "numba" if HAVE_NUMBA else "numpy"
    if name.startswith("numba") and not HAVE_NUMBA:
        raise ValueError(f"plant config: simulation.backend = {name!r} but numba is not installed; "
                         "allowed: 'auto', 'numpy' (or install numba)")
    return name


def rk4_advance(backend, x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, record_states=False,
                record_outputs=True, outputs=None):
    """Advance ``x`` (n_scen, 11) in place by ``load.shape[1]`` steps; return (outputs (n_out, n_scen, n)
    or None when ``record_outputs`` is false (numba backend only), states (N_STATES, n_scen, n) or None).

    ``outputs``: indices into OUTPUT_NAMES of the outputs to record, in that order (None: all N_OUTPUTS);
    the numba kernel writes only those, the other backends compute all and return the selected rows."""
    n_scen, n = load.shape
    sel = np.arange(N_OUTPUTS, dtype=np.int64) if outputs is None else np.asarray(outputs, dtype=np.int64)
    if sel.ndim != 1 or np.any((sel < 0) | (sel >= N_OUTPUTS)):
        raise ValueError(f"rk4_advance: outputs = {outputs!r}; allowed: indices 0..{N_OUTPUTS - 1} into OUTPUT_NAMES")
    if backend == "numba":
        out = np.empty((sel.size, n_scen, n)) if record_outputs else np.empty((sel.size, 0, 0))
        states = np.empty((N_STATES, n_scen, n)) if record_states else np.empty((N_STATES, 0, 0))
        _rk4_numba_simd(x, np.ascontiguousarray(load), np.ascontiguousarray(ua), np.ascontiguousarray(ub),
                        np.ascontiguousarray(phase, dtype=np.float64), float(u_amp),
                        np.ascontiguousarray(beta, dtype=np.float64), np.ascontiguousarray(c, dtype=np.float64),
                        np.ascontiguousarray(n1, dtype=np.float64), p, float(h), out, states,
                        bool(record_states), bool(record_outputs), sel)
        return (out if record_outputs else None), (states if record_states else None)
    out = np.empty((N_OUTPUTS, n_scen, n))
    states = np.empty((N_STATES, n_scen, n)) if record_states else np.empty((N_STATES, 0, 0))
    args = (x, np.ascontiguousarray(load), np.ascontiguousarray(ua), np.ascontiguousarray(ub),
            np.ascontiguousarray(phase, dtype=np.float64), float(u_amp),
            np.ascontiguousarray(beta, dtype=np.float64), np.ascontiguousarray(c, dtype=np.float64),
            np.ascontiguousarray(n1, dtype=np.float64), p, float(h), out, states, bool(record_states))
    if backend == "numba-scalar":
        _rk4_numba_scalar(*args)
    else:
        _rk4_numpy(*args)
    if outputs is not None:
        out = out[sel]
    return out, (states if record_states else None)
