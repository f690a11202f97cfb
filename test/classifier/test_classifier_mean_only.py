"""SPEC section 4's claim, proved: in ``paper`` mode W4 -- hence B -- depends only on the window mean."""
import numpy as np

from backlash_monitor.classifier.cpn import (
    PAPER, PAPER_CORRECTED, CounterPropagationNetwork, paper_w4_from_mean)


def _net(variant=PAPER):
    rng = np.random.default_rng(3)
    pats = rng.normal(size=(6, 2048)) * 0.4 + np.array([-0.3, -0.1, 0.05, 0.2, 0.3, 0.5])[:, None]
    return CounterPropagationNetwork.from_pattern_windows(pats, variant=variant)


def _equal_mean_pair():
    t = np.arange(2048)
    a = np.sin(2 * np.pi * t / 300.0)
    a = a - a.mean() + 0.12                                        # a smooth oscillation
    b = np.where(t < 700, -2.0, 1.0)                               # a step, totally different shape
    b = b - b.mean() + 0.12
    assert abs(a.mean() - b.mean()) < 1e-12 and np.std(a) != np.std(b)
    return a, b


def test_equal_mean_different_shape_gives_identical_b_in_paper_mode():
    net = _net(PAPER)
    a, b = _equal_mean_pair()
    np.testing.assert_allclose(net.b(a), net.b(b), rtol=1e-9, atol=1e-12)
    ra, rb = net.process(a), net.process(b)
    np.testing.assert_array_equal(ra.winners, rb.winners)


def test_paper_w4_is_a_function_of_the_mean_alone():
    net = _net(PAPER)
    rng = np.random.default_rng(4)
    for _ in range(25):
        x = rng.normal(size=2048) * rng.uniform(0.1, 3) + rng.normal() * 0.4
        np.testing.assert_allclose(net.process(x).w4,
                                   paper_w4_from_mean(x.mean(), net.m3, 2048, epochs=net.epochs,
                                                      l1=net.l1, l2=net.l2), rtol=1e-9, atol=1e-12)


def test_corrected_variant_also_needs_only_mean_and_rms():
    net = _net(PAPER_CORRECTED)
    rng = np.random.default_rng(5)
    for _ in range(10):
        x = rng.normal(size=2048) * rng.uniform(0.1, 3) + rng.normal() * 0.4
        np.testing.assert_allclose(
            net.process(x).w4,
            paper_w4_from_mean(x.mean(), net.m3, 2048, rms=np.sqrt(np.mean(x * x)),
                               variant=PAPER_CORRECTED), rtol=1e-9, atol=1e-12)


def test_paper_mode_is_a_nearest_neighbour_on_the_mean():
    """Shifting a window by a constant moves B exactly like shifting its mean."""
    net = _net(PAPER)
    rng = np.random.default_rng(6)
    means = net.m3
    for i in range(6):
        x = rng.normal(size=2048)
        x = x - x.mean() + means[i]          # a noise window with pattern i's mean
        assert net.classify(x)[0] == i
