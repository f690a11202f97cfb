"""The paper's counter-propagation equations (eq. 11-33), each against a hand-computed small case."""
import numpy as np
import pytest

from backlash_monitor.classifier.cpn import (
    PAPER, PAPER_CORRECTED, CounterPropagationNetwork, b_margin, b_vector, grossberg_step, initial_w1,
    initial_w2, kohonen_step, normalise_input, pattern_means, w4_from_w2)


def test_eq12_divides_by_sum_of_squares_not_norm():
    x = np.array([1.0, 2.0, 2.0])            # sum of squares 9, norm 3
    np.testing.assert_allclose(normalise_input(x, PAPER), [1 / 9, 2 / 9, 2 / 9])
    # eq. 11 (X1'X1 = 1) is NOT met by eq. 12: X1'X1 = 1/9
    assert normalise_input(x, PAPER) @ normalise_input(x, PAPER) == pytest.approx(1 / 9)
    np.testing.assert_allclose(normalise_input(x, PAPER_CORRECTED), [1 / 3, 2 / 3, 2 / 3])
    assert normalise_input(x, PAPER_CORRECTED) @ normalise_input(x, PAPER_CORRECTED) == pytest.approx(1.0)


def test_normalise_rejects_zero_window_and_unknown_variant():
    with pytest.raises(ValueError, match="all-zero"):
        normalise_input(np.zeros(4))
    with pytest.raises(ValueError, match="allowed: paper, paper_corrected"):
        normalise_input(np.ones(4), "textbook")


def test_eq13_14_20_21_initial_weights():
    m2 = np.array([[1.0, 3.0], [2.0, 2.0], [-1.0, -3.0]])
    m3 = pattern_means(m2)                                  # eq. 14
    np.testing.assert_allclose(m3, [2.0, 2.0, -2.0])
    np.testing.assert_allclose(initial_w1(m3, 4), [[2] * 4, [2] * 4, [-2] * 4])   # eq. 13
    np.testing.assert_allclose(initial_w2(m3), np.full((3, 3), 2 / 3))           # eq. 20-21: m1 = 2/3


def test_eq15_18_kohonen_winner_and_wta_update():
    w1 = np.array([[1.0, 0.0], [0.0, 1.0], [0.5, 0.5]])
    x1 = np.array([0.2, 0.8])
    new, y1, t = kohonen_step(w1, x1, l1=0.1)
    # E1 = [0.2, 0.8, 0.5] -> winner 1 (eq. 15-16), Y1 one-hot (eq. 17)
    assert t == 1
    np.testing.assert_array_equal(y1, [0, 1, 0])
    # eq. 18: W1(1,:) = [0,1] + 0.1*([0.2,0.8]-[0,1]) = [0.02, 0.98]; other rows untouched
    np.testing.assert_allclose(new, [[1.0, 0.0], [0.02, 0.98], [0.5, 0.5]])


def test_eq16_tie_goes_to_first_neuron():
    _, _, t = kohonen_step(np.ones((3, 2)), np.array([1.0, 1.0]), 0.1)
    assert t == 0


def test_eq22_23_grossberg_paper_sign_moves_away_from_target():
    w2 = np.full((3, 3), 1.0)
    x2 = np.array([0.0, 1.0, 0.0])
    z1 = np.full(3, 0.5)
    # Y2 = W2 X2 = [1,1,1]; paper: W2(:,1) += 0.09*(1-0.5)*1 = +0.045 -> 1.045 (away from 0.5)
    new = grossberg_step(w2, x2, z1, 0.09, PAPER)
    expected = np.full((3, 3), 1.0)
    expected[:, 1] = 1.045
    np.testing.assert_allclose(new, expected)
    # textbook outstar: towards the target, 1 - 0.045
    expected[:, 1] = 0.955
    np.testing.assert_allclose(grossberg_step(w2, x2, z1, 0.09, PAPER_CORRECTED), expected)


def test_eq26_28_t2_w3_w4():
    w2 = np.array([[1.0, 5.0, 2.0], [4.0, 0.0, 3.0], [5.0, 1.0, 1.0]])
    # T2 = 5 first met in row 0 -> W3 = [1, 5, 2] -> W4 = [5, 2, 1]
    np.testing.assert_allclose(w4_from_w2(w2), [5.0, 2.0, 1.0])


def test_eq31_33_b_vector_and_index():
    w5 = np.array([[3.0, 2.0, 1.0], [6.0, 5.0, 4.0], [0.0, 0.0, 0.0]])
    w6 = np.array([3.5, 2.0, 0.5])
    b = b_vector(w6, w5)
    np.testing.assert_allclose(b, [1.0, 9.0, 6.0])
    assert int(np.argmin(b)) == 0
    assert b_margin(b) == pytest.approx(6.0)


def test_one_epoch_by_hand_paper():
    # 2 neurons, 2 samples. M3 = [1, -1] -> W1 = [[1,1],[-1,-1]], W2 = 0 (m1 = 0).
    net = CounterPropagationNetwork(np.array([1.0, -1.0]), epochs=1, l1=0.5, l2=0.1)
    x = np.array([1.0, 3.0])                # S = 10 -> X1 = [0.1, 0.3]; m2 = 2
    r = net.process(x)
    # E1 = [0.4, -0.4] -> t = 0; W1(0) = [1,1] + 0.5([0.1,0.3]-[1,1]) = [0.55, 0.65]
    np.testing.assert_allclose(r.w1, [[0.55, 0.65], [-1.0, -1.0]])
    # Y2 = W2 X2 = [0, 0]; W2(:,0) += 0.1*(0-2)*1 = -0.2
    np.testing.assert_allclose(r.w2, [[-0.2, 0.0], [-0.2, 0.0]])
    np.testing.assert_allclose(r.w4, [0.0, -0.2])
    assert list(r.winners) == [0]


def test_batch_equals_single_and_patterns_classify_themselves():
    rng = np.random.default_rng(1)
    pats = rng.normal(size=(6, 64)) + np.linspace(-1, 1, 6)[:, None]
    net = CounterPropagationNetwork.from_pattern_windows(pats)
    batch = net.process_batch(pats).w4
    for i in range(6):
        np.testing.assert_allclose(net.process(pats[i]).w4, batch[i])
        idx, b = net.classify(pats[i])
        assert idx == i and b[i] == 0.0


def test_rows_of_w2_stay_identical_in_both_variants():
    rng = np.random.default_rng(2)
    pats = rng.normal(size=(6, 128)) + np.linspace(-1, 1, 6)[:, None]
    for variant in (PAPER, PAPER_CORRECTED):
        net = CounterPropagationNetwork.from_pattern_windows(pats, variant=variant)
        w2 = net.process_batch(rng.normal(size=(20, 128)) + 0.3).w2
        np.testing.assert_array_equal(w2, np.broadcast_to(w2[:, :1, :], w2.shape))
