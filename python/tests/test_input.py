"""Input as a physicist writes it: pint quantities wherever a unit is taken, texts with a unit
inside arrays, and shape() over an array of rates."""
import math
import pickle

import numpy as np
import pint
import pytest

import whirl

Q = pint.UnitRegistry()
SI = dict(length=0.6, mass=0.05)
U = whirl.Units(**SI)


def test_pint_scalars_are_the_command_lines_units():
    want = whirl.shape(2 * math.pi * 4, 2, **SI)
    assert whirl.shape(4 * Q.Hz, 2, length=60 * Q.cm, mass=50 * Q.g) == want
    assert whirl.shape("4Hz", 2, length="60cm", mass="50g") == want
    # 4 Hz is 4 turns a second, as "4Hz" on the command line (pint alone would make it 4 rad/s)
    assert whirl.shape(240 * Q.rpm, 2, **SI).omega == pytest.approx(want.omega, rel=1e-15)
    assert whirl.shape((8 * math.pi) * Q("rad/s"), 2, **SI) == want
    assert whirl.shape(0.004 * Q.kHz, 2, **SI).omega == pytest.approx(want.omega, rel=1e-15)
    # a dimensionless quantity is its number
    assert whirl.shape(3.0 * Q.dimensionless, 2) == whirl.shape(3.0, 2)
    assert whirl.critical(2, tip_mass=5 * Q.g, **SI)[1] == whirl.critical(2, tip_mass=0.005,
                                                                          **SI)[1]


def test_pint_units_of_the_chain():
    assert whirl.Units(length=60 * Q.cm, mass=50 * Q.g) == U
    assert whirl.Units(length=0.6, gravity=1 * Q.g0).gravity == 9.80665  # pint's standard g
    assert whirl.Units(length=0.6, gravity=981 * Q("cm/s^2")).gravity == pytest.approx(9.81)
    with pytest.raises(ValueError, match=r"gravity must be a gravity \(m/s\*\*2\)"):
        whirl.Units(length=0.6, gravity=3 * Q.m)


def test_pint_drags_damping_and_times():
    kw = dict(links=8, linear=True, units=U)
    assert (whirl.stability(4 * Q.Hz, 2, damping=1e-6 * Q("kg m^2/s"), **kw)
            == whirl.stability(8 * math.pi, 2, damping=1e-6, **kw))
    assert (whirl.driven(3 * Q.Hz, 1, 1 * Q.cm, air_drag=0.01 * Q("kg/(m s)"),
                         air_drag_quadratic=2 * Q("g/m^2"), units=U)
            == whirl.driven(6 * math.pi, 1, 0.01, air_drag=0.01, air_drag_quadratic=0.002,
                            units=U))
    runs = []
    for dt, t_end, radius, drag in ((2 * Q.ms, 0.05 * Q.s, 5 * Q.mm, 1e-3 * Q("kg/(m s)")),
                                    ("2ms", "50ms", "5mm", 1e-3)):
        sim = whirl.Simulation(6, omega=4 * Q.Hz, drive_radius=radius, air_drag=drag, units=U)
        sim.set_steady(1)
        runs.append(sim.run(t_end, dt))
    assert runs[0] == runs[1]


def test_pint_refused_where_it_cannot_apply():
    with pytest.raises(ValueError, match="omega=4 hertz needs the chain's length"):
        whirl.shape(4 * Q.Hz, 2)  # dimensionless units: a unit needs SI, as "4Hz" does
    with pytest.raises(ValueError, match=r"omega must be a rate \(rad/s\), got 4 meter"):
        whirl.shape(4 * Q.m, 2, **SI)
    with pytest.raises(ValueError, match="air_drag must be a drag"):
        whirl.driven(3.0, 1, 0.01, air_drag=1 * Q("kg/m^2"), **SI)
    sim = whirl.Simulation(4, omega=2.0, units=U)
    with pytest.raises(TypeError, match="perturb takes a number without a unit"):
        sim.set_steady(1, perturb=1 * Q.m)


def test_texts_and_pint_inside_arrays():
    rates = 2 * math.pi * np.array([4.0, 5.0, 6.0])
    want = whirl.sweep([1, 2], rates, links=6, **SI)
    for given in (["4Hz", "5Hz", "6Hz"], np.array(["4Hz", "5 Hz", "360rpm"]),
                  np.array([4, 5, 6]) * Q.Hz, [4 * Q.Hz, "5Hz", 2 * math.pi * 6]):
        got = whirl.sweep([1, 2], given, links=6, **SI)
        for k in (1, 2):
            np.testing.assert_allclose(got[k]["omega"], want[k]["omega"], rtol=1e-15)
            np.testing.assert_allclose(got[k]["tip_r"], want[k]["tip_r"], rtol=1e-12)
    m = whirl.stability_map(["25rad/s", "30rad/s"], 2, 6, **SI)
    np.testing.assert_array_equal(m, whirl.stability_map([25.0, 30.0], 2, 6, **SI))
    with pytest.raises(ValueError, match=r"omega\[1\] must be a number"):
        whirl.sweep(1, ["4Hz", "fast"], **SI)
    with pytest.raises(ValueError, match="needs the chain's length"):
        whirl.sweep(1, ["4Hz", "5Hz"])


@pytest.mark.parametrize("links", [None, 6])
def test_shape_over_an_array_of_rates(links):
    rates = [25.0, "5Hz", 40 * Q("rad/s")]
    batch = whirl.shape(rates, 2, links=links, points=21, **SI)
    assert isinstance(batch, whirl.Shapes) and isinstance(batch, list) and len(batch) == 3
    singles = [whirl.shape(w, 2, links=links, points=21, **SI) for w in rates]
    assert batch == singles  # each solved as alone, in the order given
    assert [s.omega for s in batch] == pytest.approx([25.0, 10 * math.pi, 40.0], rel=1e-15)
    assert pickle.loads(pickle.dumps(batch)) == batch
    # its table: whirl sweep's columns, and the sweep's numbers
    table = batch.as_dict()
    assert list(table) == ["omega [rad/s]", "mode", "tip_r [m]", "max_r [m]",
                           "top_tension [N]", "depth [m]", "nodes"]
    branch = whirl.sweep(2, [s.omega for s in batch], links=links, **SI)[2]
    np.testing.assert_allclose(table["tip_r [m]"], branch["tip_r"], rtol=1e-9)
    np.testing.assert_array_equal(table["nodes"], branch["node_count"])
    frame = batch.to_pandas()
    np.testing.assert_array_equal(frame["depth [m]"].to_numpy(), [s.depth for s in batch])
    # a 0-d array is one rate, a list of one a batch of one
    assert isinstance(whirl.shape(np.array(25.0), 2, **SI), whirl.Shape)
    assert len(whirl.shape([25.0], 2, **SI)) == 1
    with pytest.raises(whirl.InvalidInput, match="mode 2 does not exist at omega=1"):
        whirl.shape([25.0, 1.0], 2, links=links, **SI)
