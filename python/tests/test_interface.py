"""The interface solver from Python: every verification case gives the waves `petroscope interface --case`
gives, and the closed forms hold (Fresnel at normal incidence, Brewster's angle, total reflection)."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import petroscope


def cli_waves(binary, case):
    return json.loads(subprocess.run([binary, "interface", "--case", str(case), "--json"], check=True, capture_output=True, text=True).stdout)


def test_every_verification_case_gives_the_command_lines_waves(repository):
    binary = os.environ.get("PETROSCOPE_BINARY")
    if not binary:
        pytest.skip("the command-line tool is not built")
    cases = sorted((repository / "verification" / "cases").glob("*.json"))
    assert len(cases) > 40
    for case in cases:
        result = petroscope.interface_case(case)
        expected = cli_waves(binary, case)
        assert len(result.waves) == len(expected["waves"]), case.name
        for wave, reference in zip(result.waves, expected["waves"]):
            assert (wave.kind, wave.mode, wave.evanescent) == (reference["kind"], reference["mode"], reference["evanescent"]), case.name
            n = reference["n"] if isinstance(reference["n"], float) else complex(*reference["n"])
            assert wave.n == n, case.name
            assert wave.power == reference["power"], case.name
            np.testing.assert_array_equal(wave.direction, reference["direction"])
            np.testing.assert_array_equal(wave.ray_direction, reference["ray_direction"])
            np.testing.assert_array_equal(wave.stokes, reference["stokes"])


def test_fresnel_and_brewster_hold():
    air, glass = petroscope.Medium(1.0), petroscope.Medium(1.5)
    normal = petroscope.interface(air, glass, direction=(0, 0, 1), polarization="s")
    reflected = [w for w in normal.waves if w.kind == "reflected"][0]
    assert reflected.power == pytest.approx(((1.5 - 1) / (1.5 + 1)) ** 2, abs=1e-15)  # R = ((n − 1)/(n + 1))²
    assert sum(w.power for w in normal.waves) == pytest.approx(1.0, abs=1e-14)
    brewster = math.atan(1.5)  # tan θ_B = n₂/n₁
    direction = (math.sin(brewster), 0.0, math.cos(brewster))
    p_wave = petroscope.interface(air, glass, direction=direction, polarization="p")
    assert [w.power for w in p_wave.waves if w.kind == "reflected"][0] < 1e-28
    # Beyond the critical angle from glass into air everything is reflected; the transmitted wave is evanescent.
    steep = math.radians(60.0)
    total = petroscope.interface(glass, air, direction=(math.sin(steep), 0.0, math.cos(steep)))
    assert [w.power for w in total.waves if w.kind == "reflected"][0] == pytest.approx(1.0, abs=1e-14)
    assert all(w.evanescent for w in total.waves if w.kind == "transmitted")


def test_calcite_splits_normal_light_into_ordinary_and_extraordinary():
    calcite = petroscope.Medium.of_mineral("calcite", 589.3, euler_zyz_deg=(0, 45, 0))  # optic axis 45° from the normal
    result = petroscope.interface(petroscope.Medium(1.0), calcite, direction=(0, 0, 1))
    transmitted = {w.mode: w for w in result.waves if w.kind == "transmitted"}
    assert set(transmitted) == {"ordinary", "extraordinary"}
    n_o, _, n_e = petroscope.mineral("calcite").principal_n(589.3)
    assert transmitted["ordinary"].n.real == pytest.approx(n_o, abs=1e-12)
    # The extraordinary ray walks off the wave normal (its direction stays the normal's at normal incidence).
    assert transmitted["extraordinary"].ray_direction[0] != pytest.approx(0.0, abs=1e-3)


def test_a_waves_mueller_matrix_gives_its_stokes_vector_for_any_incident_polarization():
    # Calcite tilted so that its modes take mixed polarizations: one solve's Mueller matrix against solves
    # with each polarization.
    calcite = petroscope.Medium.of_mineral("calcite", 589.3, euler_zyz_deg=(30, 50, 10))
    air = petroscope.Medium(1.0)
    direction = (0.3, -0.4, math.sqrt(1 - 0.25))
    muellers = [w.mueller for w in petroscope.interface(air, calcite, direction=direction).waves]
    assert all(m is not None and m.shape == (4, 4) for m in muellers)
    for stokes in ([1, 0, 0, 0], [1, 1, 0, 0], [1, 0, 0.6, 0.8], [1, -0.3, 0.4, -0.5]):
        waves = petroscope.interface(air, calcite, direction=direction, polarization=stokes).waves
        for wave, mueller in zip(waves, muellers):
            np.testing.assert_allclose(mueller @ np.array(stokes, dtype=float), wave.stokes, atol=1e-13)
    # From inside a crystal the incident wave is one mode: no Mueller matrix.
    inside = petroscope.interface(calcite, air, direction=(0, 0, 1), mode="ordinary")
    assert all(w.mueller is None for w in inside.waves)


def test_double_arithmetic_agrees_with_long_double():
    # Aragonite from air at a random-looking incidence: the same waves, powers within the tested 4e-11.
    aragonite = petroscope.Medium.of_mineral("aragonite", 589.3, euler_zyz_deg=(20, 35, -15))
    air = petroscope.Medium(1.0)
    direction = (0.5, 0.2, math.sqrt(1 - 0.29))
    exact = petroscope.interface(air, aragonite, direction=direction, polarization=(1, 0.3, -0.2, 0.5)).waves
    fast = petroscope.interface(air, aragonite, direction=direction, polarization=(1, 0.3, -0.2, 0.5), arithmetic="double").waves
    assert [w.mode for w in exact] == [w.mode for w in fast]
    for a, b in zip(exact, fast):
        assert abs(a.power - b.power) < 1e-10
        np.testing.assert_allclose(a.stokes, b.stokes, atol=1e-10)
        np.testing.assert_allclose(a.direction, b.direction, atol=1e-12)
    with pytest.raises(ValueError, match="arithmetic"):
        petroscope.interface(air, aragonite, direction=direction, arithmetic="float")


def test_bad_interface_input():
    air, glass = petroscope.Medium(1.0), petroscope.Medium(1.5)
    with pytest.raises(ValueError, match="toward medium 2|direction"):
        petroscope.interface(air, glass, direction=(0, 0, -1))
    with pytest.raises(ValueError, match="polarization"):
        petroscope.interface(air, glass, direction=(0, 0, 1), polarization="sideways")
    with pytest.raises(ValueError, match="mode"):
        petroscope.interface(petroscope.Medium.of_mineral("calcite", 589.3), air, direction=(0, 0, 1), mode="s+p")
    with pytest.raises(ValueError, match="refractive indices"):
        petroscope.interface(air, petroscope.Medium(-1.0), direction=(0, 0, 1))


def test_the_verification_cases_pass():
    tests = petroscope.verify(own_sweeps=False)
    assert len(tests) > 40
    failed = [t["name"] for t in tests if not t["passed"]]
    assert failed == []
    assert all(check["passed"] for t in tests for check in t["checks"])


def test_optically_active_quartz_sends_two_circular_waves_along_its_axis():
    # Along the optic axis the two waves of quartz are circular with n = n̄ ∓ g₃₃/2, n̄ = √(n_o² + g₃₃²/4), and
    # both have the admittance n̄: R = ((n̄ − 1)/(n̄ + 1))², each wave (1 − R)/2 (docs/verification.md, T8).
    air = petroscope.Medium(1.0)
    for handedness, sense in (("right", 1.0), ("left", -1.0)):
        quartz = petroscope.Medium.of_mineral("quartz", 589.3, handedness=handedness)
        g33 = quartz.gyration[2, 2]
        assert sense * g33 > 0 and quartz.gyration[0, 0] == pytest.approx(-g33 / 2, rel=1e-12)
        n_bar = math.hypot(quartz.principal_n[0].real, g33 / 2)
        reflectance = ((n_bar - 1) / (n_bar + 1)) ** 2
        result = petroscope.interface(air, quartz, direction=(0, 0, 1), polarization="s")
        fast, slow = [w for w in result.waves if w.kind == "transmitted"]
        assert (fast.mode, slow.mode) == ("fast", "slow")
        assert abs(fast.n - (n_bar - abs(g33) / 2)) < 1e-12 and abs(slow.n - (n_bar + abs(g33) / 2)) < 1e-12
        for wave, circular in ((fast, sense), (slow, -sense)):
            assert wave.power == pytest.approx((1 - reflectance) / 2, abs=1e-12)
            assert wave.stokes[3] == pytest.approx(circular * wave.power, abs=1e-12)  # right circular: S3 = +S0
            np.testing.assert_array_equal(wave.d_direction, np.zeros(3))
        # The same crystal given by its indices and gyration.
        same = petroscope.Medium(quartz.principal_n, gyration=np.diag(quartz.gyration))
        again = petroscope.interface(air, same, direction=(0, 0, 1), polarization="s")
        assert [w.power for w in again.waves] == [w.power for w in result.waves]


def test_bad_optical_activity_input():
    with pytest.raises(ValueError, match="right or left"):
        petroscope.Medium.of_mineral("quartz", 589.3, handedness="sideways")
    with pytest.raises(ValueError, match="gyration"):
        petroscope.Medium(1.5, gyration=[[0, 1e-5, 0], [0, 0, 0], [0, 0, 0]])
    with pytest.raises(ValueError, match="gyration"):
        petroscope.Medium(1.5, gyration=[math.nan, 0, 0])
    quartz = petroscope.Medium.of_mineral("quartz", 589.3)
    with pytest.raises(ValueError, match="optically active"):
        petroscope.interface(quartz, petroscope.Medium(1.0), direction=(0, 0, 1), mode="ordinary")
