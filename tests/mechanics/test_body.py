"""Body data: the paper's preset and de Leva scaling."""

import numpy as np
import pytest

from formopt.mechanics.body import DE_LEVA, paper_body, scaled_body


def test_paper_body():
    body = paper_body()
    assert body.mass == pytest.approx(73.0)
    thigh = body["thigh"]
    assert thigh.length == pytest.approx(0.402)
    assert thigh.inertia_proximal == pytest.approx(0.557)
    # Table 1's convention: inertia about the proximal joint = m L^2 / 3
    for seg in ("thigh", "shank"):
        s = body[seg]
        assert s.inertia_proximal == pytest.approx(s.mass * s.length**2 / 3, rel=0.01)


@pytest.mark.parametrize("sex", ["male", "female"])
def test_scaling_follows_de_leva(sex):
    body = scaled_body(62.0, 1.81, sex)
    table = DE_LEVA[sex]
    assert body.mass == pytest.approx(62.0)
    for seg in ("thigh", "shank"):
        length, mass_fraction, com_fraction, gyration = table[seg]
        s = body[seg]
        assert s.mass == pytest.approx(mass_fraction * 62.0)
        assert s.length == pytest.approx(length * 1.81 / table["stature"])
        assert -s.com[1] == pytest.approx(com_fraction * s.length)
        assert s.inertia_com == pytest.approx(s.mass * (gyration * s.length) ** 2)
    foot = body["foot"]
    assert foot.landmarks["heel"][0] < 0 < foot.landmarks["forefoot"][0]
    assert foot.inertia_com > 0


def test_scaling_is_proportional():
    """Twice as tall: lengths double; twice as heavy: masses double."""
    a, b = scaled_body(60.0, 1.7), scaled_body(120.0, 3.4)
    for seg in ("thigh", "shank", "foot"):
        assert b[seg].mass == pytest.approx(2 * a[seg].mass)
        assert np.allclose(np.array(b[seg].com), 2 * np.array(a[seg].com))


def test_scaling_rejects_unknown_sex():
    with pytest.raises(ValueError, match="sex"):
        scaled_body(60.0, 1.7, "x")
