"""The live microscope in a real browser: `petroscope serve` started as a user starts it, its page loaded
in headless Chromium and driven through the DevTools protocol as a student would drive it (dragging the
view, pressing keys, choosing a plate, swinging in the Bertrand lens), and what the page shows checked
against the physics: against the library's own render of the same view (Python binding), extinction at
the angles grain_optics gives, the gypsum plate's addition and subtraction colours, the centred cross of a
uniaxial crystal cut across its optic axis. The frame rate while dragging is reported, not asserted
(speed lives in benchmarks)."""

import base64
import json
import math
import os
import subprocess
import time

import numpy
import pytest

from devtools import Browser, find_chromium
from served import running_server

BINARY = os.environ.get("PETROSCOPE_BINARY")
SCREENSHOTS = os.environ.get("PETROSCOPE_SCREENSHOT_DIR")  # set to write the pictures of docs/browser.md
VIEW = 512  # the eyepiece canvas, CSS pixels = canvas pixels

pytestmark = pytest.mark.skipif(not BINARY or not find_chromium(), reason="needs the petroscope binary and Chromium")


@pytest.fixture(scope="module")
def server():
    with running_server(BINARY) as (_, port):
        yield f"http://127.0.0.1:{port}/"


@pytest.fixture(scope="module")
def page(server):
    with Browser() as browser:
        tab = browser.new_page()
        tab.set_viewport(1000, 780)
        tab.navigate(server)
        wait_until_drawn(tab)
        yield tab
        assert tab.console_errors == []


@pytest.fixture(autouse=True)
def microscope(page):
    """Each test starts from the page's first view: granite, crossed polars, no plate, stage at 0."""
    page.evaluate("""(() => {
        document.querySelector('input[name=specimen][value=section]').checked = true;
        document.getElementById('section').value = 'granite';
        document.getElementById('plate').value = 'none';
        document.getElementById('analyzer').checked = true;
        document.getElementById('bertrand').checked = false;
        document.getElementById('euler').value = '';
        document.getElementById('section').dispatchEvent(new Event('change'));
        const stage = document.getElementById('stage'); stage.value = '0'; stage.dispatchEvent(new Event('change'));
    })()""")
    wait_until_drawn(page)
    return page


def wait_until_drawn(page, timeout_s=60):
    page.wait_for("window.petroscope && petroscope.ready && !petroscope.state.dirty", timeout_s=timeout_s)


def canvas_rgb(page):
    """The eyepiece canvas as an array of 8-bit sRGB codes, rows from the top."""
    encoded = page.evaluate("""(() => {
        const data = document.getElementById('view').getContext('2d').getImageData(0, 0, 512, 512).data;
        let text = ''; for (let k = 0; k < data.length; k += 8192) text += String.fromCharCode(...data.subarray(k, k + 8192));
        return btoa(text); })()""")
    return numpy.frombuffer(base64.b64decode(encoded), dtype=numpy.uint8).reshape(VIEW, VIEW, 4)[:, :, :3].astype(int)


def canvas_centre(page):
    box = page.evaluate("(() => { const b = document.getElementById('view').getBoundingClientRect(); return [b.left, b.top]; })()")
    return box[0] + VIEW / 2, box[1] + VIEW / 2


def turn_stage_by_keys(page, degrees):
    """Whole degrees, counter-clockwise, in 45° and 1° steps as a user presses them."""
    whole = round(degrees)
    key = "ArrowLeft" if whole > 0 else "ArrowRight"
    for _ in range(abs(whole) // 45):
        page.key(key, shift=True)
    for _ in range(abs(whole) % 45):
        page.key(key)
    wait_until_drawn(page)


def choose(page, element_id, value):
    page.evaluate(f"(() => {{ const e = document.getElementById('{element_id}'); e.value = '{value}'; "
                  "e.dispatchEvent(new Event('change')); })()")
    wait_until_drawn(page)


def set_checkbox(page, element_id, checked):
    if page.evaluate(f"document.getElementById('{element_id}').checked") != checked:
        page.evaluate(f"document.getElementById('{element_id}').click()")
    wait_until_drawn(page)


def screenshot(page, name):
    if SCREENSHOTS:
        page.screenshot(os.path.join(SCREENSHOTS, name))


def centre_grain(page):
    """The numbers of the grain under the crosshair (the page's default pick)."""
    page.wait_for("petroscope.state.numbers !== null")
    return page.evaluate("petroscope.state.numbers")


def srgb_codes(linear):
    linear = numpy.clip(linear, 0.0, 1.0)
    encoded = numpy.where(linear <= 0.0031308, 12.92 * linear, 1.055 * numpy.power(linear, 1 / 2.4) - 0.055)
    return numpy.rint(255 * encoded).astype(int)


def test_the_view_at_a_turned_stage_is_the_librarys_render_at_that_stage(page):
    """The page composes the picture from five harmonics; the library renders it directly. 8-bit codes may
    differ by one where the page's encoding table rounds the other way."""
    petroscope = pytest.importorskip("petroscope")
    turn_stage_by_keys(page, 37)
    shown = canvas_rgb(page)
    source = os.path.join(os.environ["PETROSCOPE_SOURCE_DIR"], "thin_sections", "granite")
    expected = srgb_codes(petroscope.orthoscope(petroscope.read_section(source), stage_deg=37.0).image)
    assert numpy.abs(shown - expected).max() <= 1


def test_turning_the_stage_brings_a_grain_in_and_out_of_extinction(page):
    grain = centre_grain(page)
    extinction = grain["extinction_stage_deg"]
    turn_stage_by_keys(page, extinction)
    dark = canvas_rgb(page)[VIEW // 2, VIEW // 2]
    turn_stage_by_keys(page, 45)
    bright = canvas_rgb(page)[VIEW // 2, VIEW // 2]
    # Off extinction by at most half a degree: the intensity is sin²(2·0.5°) = 3e-4 of the brightest.
    assert dark.max() <= 12, (grain, dark)
    assert bright.sum() >= 10 * max(dark.sum(), 1), (grain, dark, bright)


def test_dragging_turns_the_stage_by_the_angle_swept(page):
    x, y = canvas_centre(page)
    radius = 150
    arc = [(x + radius * math.cos(math.radians(a)), y - radius * math.sin(math.radians(a))) for a in range(2, 92, 2)]
    page.mouse_drag_along(arc, start=(x + radius, y))
    wait_until_drawn(page)
    assert page.evaluate("petroscope.state.stageDeg") == pytest.approx(90.0, abs=0.5)


def test_the_gypsum_plate_turns_first_order_grey_blue_or_yellow(page):
    """The grain under the crosshair, first-order grey, at 45° with its slow direction parallel to the
    plate's slow direction (NE-SW): retardations add to second-order blue; perpendicular, they subtract to
    first-order yellow (Michel-Lévy)."""
    grain = centre_grain(page)
    assert 50 < grain["retardation_nm"] < 250, grain
    choose(page, "plate", "gypsum")
    turn_stage_by_keys(page, (45 - grain["slow_azimuth_deg"]) % 180)
    red, _, blue = canvas_rgb(page)[VIEW // 2, VIEW // 2]
    assert blue > red + 30, "addition should be blue"
    screenshot(page, "browser-gypsum.png")
    turn_stage_by_keys(page, 90)
    red, _, blue = canvas_rgb(page)[VIEW // 2, VIEW // 2]
    assert red > blue + 30, "subtraction should be yellow"


def test_the_bertrand_lens_shows_the_centred_cross_of_calcite_cut_across_its_axis(page):
    """Crossed polars, a uniaxial crystal cut ⟂ its optic axis: dark isogyres along E-W and N-S through the
    centre, bright between; turning the stage leaves the cross where it is."""
    page.evaluate("document.querySelector('input[name=specimen][value=crystal]').click()")
    choose(page, "mineral", "calcite")
    choose(page, "cut", "optic-axis")
    set_checkbox(page, "bertrand", True)
    screenshot(page, "browser-bertrand-calcite.png")
    for _ in range(2):
        image = canvas_rgb(page).sum(axis=2)
        centre, r = VIEW // 2, 150
        on_arms = [image[centre, centre + r], image[centre, centre - r], image[centre + r, centre], image[centre - r, centre]]
        d = int(r / math.sqrt(2))
        between = [image[centre + d, centre + d], image[centre - d, centre - d], image[centre + d, centre - d], image[centre - d, centre + d]]
        assert max(on_arms) < 0.15 * min(between), (on_arms, between)
        turn_stage_by_keys(page, 30)


def test_the_form_of_quartz_turns_the_spirals_of_the_mica_plate(page):
    """A 1 mm quartz plate cut across its axis under the Bertrand lens with the mica (λ/4) plate shows Airy's
    spirals, whose sense gives the handedness: the page's figure of each form is the library's. A mirror across
    the plate's NE-SW axis turns right quartz into left and keeps the plate, but swaps polarizer and analyzer,
    which changes this figure by under 1e-3 (linear): so left is right's mirror image to about a code, and far
    from right itself."""
    petroscope = pytest.importorskip("petroscope")
    page.evaluate("document.querySelector('input[name=specimen][value=crystal]').click()")
    choose(page, "mineral", "quartz")
    choose(page, "cut", "optic-axis")
    choose(page, "crystal-thickness", "1000")
    choose(page, "plate", "mica")
    set_checkbox(page, "bertrand", True)
    shown = {}
    for hand in ("right", "left"):
        choose(page, "handedness", hand)
        shown[hand] = canvas_rgb(page)
        expected = srgb_codes(petroscope.conoscope(mineral="quartz", cut="optic-axis", thickness_um=1000.0, plate="mica",
                                                   handedness=hand).image)
        assert numpy.abs(shown[hand] - expected).max() <= 1, hand
    screenshot(page, "browser-quartz-left-mica.png")
    mirrored = shown["right"].transpose(1, 0, 2)
    assert numpy.abs(shown["left"] - mirrored).max() <= 2
    assert numpy.abs(shown["left"] - shown["right"]).max() > 60
    choose(page, "handedness", "right")
    choose(page, "crystal-thickness", "30")


def test_pushing_a_plate_in_needs_no_server_once_the_page_has_fetched_it(page):
    """While idle the page fetches the views one click away; pushing the gypsum plate in and out then
    draws at once from what it holds, and the time from the click to the drawn view is reported."""
    page.wait_for("!petroscope.prefetching && cache.has(viewQuery({plate: 'gypsum'}))", timeout_s=60)
    choose(page, "plate", "gypsum")
    choose(page, "plate", "none")
    shown = page.evaluate("petroscope.stats.views.slice(-2)")
    assert all(view["cached"] for view in shown), shown
    print("browser: plate in, plate out, drawn after (ms):", [round(view["ms"], 1) for view in shown])


def test_a_crystal_given_by_euler_angles(page):
    """Euler angles instead of a cut: calcite with its optic axis turned onto the microscope axis by
    b = 0 shows the same centred cross as the optic-axis cut."""
    page.evaluate("document.querySelector('input[name=specimen][value=crystal]').click()")
    choose(page, "mineral", "calcite")
    choose(page, "euler", "0,0,0")
    set_checkbox(page, "bertrand", True)
    image = canvas_rgb(page).sum(axis=2)
    centre, r = VIEW // 2, 150
    assert image[centre, centre + r] < 0.15 * image[centre + 106, centre + 106]
    choose(page, "euler", "")


def test_a_section_of_ones_own_is_sent_and_shown(page, tmp_path):
    """A section made with `petroscope section random` (calcite only), chosen in the page's file input as
    a user would: the server reads it, the page shows it, the numbers name its mineral."""
    folder = tmp_path / "my-calcite"
    subprocess.run([BINARY, "section", "random", "--minerals", "calcite", "--grains", "3", "--size", "96", "--name", "my calcite",
                    "-o", str(folder)], check=True, capture_output=True)
    page.set_file_input("#section-files", [folder / "section.txt", folder / "grains.png"])
    page.wait_for("document.getElementById('section').value.startsWith('upload-')", timeout_s=30)
    wait_until_drawn(page)
    assert page.evaluate("petroscope.state.view.width") == 96
    page.wait_for("petroscope.state.numbers && petroscope.state.numbers.mineral === 'calcite'", timeout_s=30)


def test_the_frame_rate_while_dragging(page):
    """Every pointer move redraws the view; the rate and the time per frame are reported."""
    x, y = canvas_centre(page)
    frames_before = page.evaluate("petroscope.stats.frames")
    started = time.monotonic()
    arc = [(x + 150 * math.cos(math.radians(a)), y - 150 * math.sin(math.radians(a))) for a in range(1, 121)]
    page.mouse_drag_along(arc, start=(x + 150, y))
    wait_until_drawn(page)
    elapsed = time.monotonic() - started
    frames = page.evaluate("petroscope.stats.frames") - frames_before
    compose_ms = sorted(page.evaluate("petroscope.stats.composeMs.slice(-%d)" % frames))
    report = {"frames": frames, "seconds": elapsed, "frames_per_second": frames / elapsed,
              "compose_ms_median": compose_ms[len(compose_ms) // 2], "view_px": VIEW}
    print("browser frame rate while dragging:", json.dumps(report))
    assert frames >= 30, report
    screenshot(page, "browser-granite.png")
