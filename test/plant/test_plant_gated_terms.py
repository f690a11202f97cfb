"""A plug-in's term ``c * (...)`` is computed by the SIMD kernel only on a tile where its factor c is non-zero on some
scenario (codegen._gated_terms): the recordings are those of the backends that compute every term at every step."""
import numpy as np

from backlash_monitor.plant import codegen, load_plant_config
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.scenarios import Scenario
from backlash_monitor.plant.simulate import PlantSimulator

BRAKE = '''
from backlash_monitor.plant.effects import Effect, Parameter


class WheelSpeedBrake(Effect):
    name = "test_gated_wheel_brake"
    balance = "wheel_torque_Nm"
    description = "a viscous brake on the wheel, -c*Omega2 (a factor times an expression: gated)"
    parameters = (Parameter("c_Nms", "N*m*s/rad", 0.0, (0.0, 1.0), "c"),)

    @staticmethod
    def term(omega2, c_Nms):
        return c_Nms * (-omega2)


class MotorTorqueShare(Effect):
    name = "test_gated_motor_share"
    balance = "motor_load_moment_pu"
    description = "a load following the motor's own torque and the penetration, k*te*(1 + penetration)"
    parameters = (Parameter("k", "1", 0.0, (-1.0, 1.0), "k"),)

    @staticmethod
    def term(te, penetration, k):
        return k * (te * (1.0 + penetration))
'''


def _run(tmp_path, backend, c, k):
    path = tmp_path / "brake.py"
    path.write_text(BRAKE)
    cat = builtin_catalogue().with_files([path])
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, "effects.test_gated_wheel_brake": True,
                                       "effects.test_gated_motor_share": True}, catalogue=cat)
    scen = [Scenario(0.005, 0.025, 0.89, seed=1 + i) for i in range(len(c))]
    sim = PlantSimulator(scen, config=cfg, noise=True, backend=backend,
                         parameters={"test_gated_wheel_brake.c_Nms": np.asarray(c, dtype=float),
                                     "test_gated_motor_share.k": np.asarray(k, dtype=float)})
    return sim, sim.run(4000)


def test_gated_terms_run_alike_on_every_backend_on_tiles_with_and_without_them(tmp_path):
    """Nine scenarios (two tiles of the SIMD kernel: 8 + 1): the brake on in scenario 2 only (the first tile), the motor
    share in scenario 8 only (the second tile); the compiled kernel skips each term on the tile where it is 0
    everywhere, the numpy backend computes both everywhere: the same recordings, and the terms do act."""
    c = [0.0, 0.0, 0.05, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    k = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.02]
    sim, out = _run(tmp_path, "numba", c, k)
    assert {e.name for e, _ in codegen._gated_terms(sim.kernel.effects)} >= {"test_gated_wheel_brake",
                                                                              "test_gated_motor_share"}
    _, ref = _run(tmp_path, "numpy", c, k)
    for name in ("a1", "a2", "omega1", "angle_difference"):
        x, y = getattr(out, name), getattr(ref, name)
        assert np.allclose(x, y, rtol=1e-9, atol=1e-9 * np.abs(y).max()), name
    _, off = _run(tmp_path, "numba", [0.0] * 9, [0.0] * 9)
    for i in (2, 8):                   # each term changes its own scenario's recording
        assert np.max(np.abs(out.omega1[i] - off.omega1[i])) > 1e-4 * np.abs(off.omega1[i]).max()
    for i in (0, 1, 3, 7):             # and no other
        assert np.array_equal(out.a1[i], off.a1[i])


def test_the_gated_kernels_source_is_the_same_in_every_process(tmp_path):
    """The kernel's source names its cache file: the gated passes are generated in one order whatever the process's
    string hashing (else every process compiles the kernel anew, ~1 min of CPU for the proposal's library)."""
    import subprocess
    import sys
    path = tmp_path / "brake.py"
    path.write_text(BRAKE)
    code = ("import hashlib, sys; from backlash_monitor.plant import codegen; "
            "from backlash_monitor.plant.catalogue import builtin_catalogue; "
            f"cat = builtin_catalogue().with_files([{str(path)!r}]); "
            "cls = tuple(c for c in cat.values() if c.kind == 'term'); "
            "assert codegen._gated_terms(cls); "
            "print(hashlib.sha256(codegen.generate_source(cls).encode()).hexdigest())")
    digests = set()
    for seed in ("1", "2", "3"):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                             env={**__import__("os").environ, "PYTHONHASHSEED": seed})
        digests.add(out.stdout.strip())
    assert len(digests) == 1
