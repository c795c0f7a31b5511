#!/usr/bin/env bash
# Regenerates the gallery: every image in docs/gallery/ and the page docs/gallery.md, from the command
# line only. Run it from the repository root:
#
#     docs/gallery.sh [PETROSCOPE_BINARY]        # default: build/petroscope
#
# The minerals come from $PETROSCOPE_MINERALS if it is set, else from minerals/ of this repository. The
# JSON sidecars are deleted (they hold absolute paths and timings, and the page lists every command), and
# the conoscope figures are 384 px square, to keep the repository small. Nothing else is written.
set -euo pipefail

binary=${1:-build/petroscope}
if [[ ! -f minerals/calcite.txt || ! -d thin_sections/granite ]]; then
    echo "gallery.sh: run me from the repository root (minerals/ and thin_sections/ not found here)" >&2
    exit 2
fi
if [[ ! -x $binary ]]; then
    echo "gallery.sh: $binary is not an executable; build it first (cmake --build build) or name it" >&2
    exit 2
fi
export PETROSCOPE_MINERALS=${PETROSCOPE_MINERALS:-$PWD/minerals}

out=docs/gallery
page=docs/gallery.md
size=384   # conoscope figures
mkdir -p "$out"
rm -f "$out"/*.png "$out"/*.gif "$out"/*.json
page_tmp=$(mktemp "docs/.gallery.md.XXXXXX")
trap 'rm -f "$page_tmp"' EXIT
started=$SECONDS

# md LINE...: appends lines to the page.
md() { printf '%s\n' "$@" >>"$page_tmp"; }

# render NAME ARGS...: runs `petroscope ARGS -o docs/gallery/NAME.png`, drops the sidecar, and leaves the
# command as the page shows it in $command.
render() {
    local name=$1
    shift
    echo "gallery.sh: $name" >&2
    local message
    if ! message=$("$binary" "$@" -o "$out/$name.png" 2>&1 >/dev/null); then
        echo "gallery.sh: failed: petroscope $* -o $out/$name.png" >&2
        echo "$message" >&2
        exit 1
    fi
    rm -f "$out/$name.png.json"
    command="petroscope$(printf ' %q' "$@") -o $out/$name.png"
}

# figure NAME CAPTION ARGS...: renders one image and puts it on the page with its caption and command.
figure() {
    local name=$1 caption=$2
    shift 2
    render "$name" "$@"
    md "**${caption}**" "" "![${name}](gallery/${name}.png)" "" '```sh' "$command" '```' ""
}

md "# Gallery" "" \
   "Every image on this page was made by [gallery.sh](gallery.sh) with the command printed under it; run" \
   "\`docs/gallery.sh build/petroscope\` from the repository root to make them all again (this page" \
   "included; about 40 s on two cores). Unless a caption says otherwise the light is white (CIE D65, 380–780 nm" \
   "every 5 nm), the polarizer is E–W and the analyzer N–S (crossed); in the conoscope figures the" \
   "objective's NA is 0.85 and the slab lies in Canada balsam (n = 1.54). Frames and angle senses are in" \
   "[conventions.md](conventions.md); the physics is summarised in [theory.md](theory.md) and every option" \
   "in [cli.md](cli.md)." ""

# ---------------------------------------------------------------------------------------------------------
md "## Conoscopic figures of ten minerals" "" \
   "Interference figures seen through the Bertrand lens. Uniaxial crystals are cut perpendicular to the" \
   "optic axis (the default for them), biaxial ones perpendicular to the acute bisectrix (their default)" \
   "unless a caption names another cut. Thicknesses are chosen so that a few isochromes show: strongly" \
   "birefringent minerals are thin, weakly birefringent ones thick." ""

figure calcite-30um "Calcite (uniaxial, negative), 30 µm, cut perpendicular to the optic axis: the dark cross and the isochromes of a strongly birefringent crystal." \
    conoscope --mineral calcite --thickness 30um --size $size
figure quartz-1mm "Quartz (uniaxial, positive), 1 mm, perpendicular to the optic axis: right-handed quartz turns the plane of polarization by 22° along the axis (more in the violet), so the cross fades out before the centre, which is lit and coloured." \
    conoscope --mineral quartz --thickness 1mm --size $size
figure zircon-200um "Zircon (uniaxial, positive, n ≈ 1.93–1.98), 200 µm: its high indices bend the rays toward the axis, so the rings are wide for its birefringence." \
    conoscope --mineral zircon --thickness 200um --size $size
figure apatite-1mm "Apatite (uniaxial, negative, birefringence 0.004), 1 mm, perpendicular to the optic axis." \
    conoscope --mineral apatite --thickness 1mm --size $size
figure muscovite-150um-45deg "Muscovite (biaxial, negative, 2V 40°), 150 µm, acute bisectrix, stage at 45°: the isogyres are hyperbolae through the melatopes." \
    conoscope --mineral muscovite --thickness 150um --stage-deg 45 --size $size
figure biotite-100um-45deg "Biotite (biaxial, negative, 2V ≈ 5°), 100 µm, acute bisectrix, stage at 45°: the cross barely opens, almost a uniaxial figure." \
    conoscope --mineral biotite --thickness 100um --stage-deg 45 --size $size
figure aragonite-60um-45deg "Aragonite (biaxial, negative, 2V 18°), 60 µm, acute bisectrix, stage at 45°: the melatopes close together, each ringed by isochromes." \
    conoscope --mineral aragonite --thickness 60um --stage-deg 45 --size $size
figure topaz-400um-45deg "Topaz (biaxial, positive, 2V 57°), 400 µm, acute bisectrix, stage at 45°: the melatopes lie near the edge of the field." \
    conoscope --mineral topaz --thickness 400um --stage-deg 45 --size $size
figure gypsum-400um "Gypsum (biaxial, positive, 2V 58°), 400 µm, acute bisectrix, stage at 0°: the optic axial plane E–W, the isogyres a cross with the melatopes on its E–W arm." \
    conoscope --mineral gypsum --thickness 400um --size $size
figure forsterite-100um-optic-axis "Forsterite (biaxial, positive, 2V 82°), 100 µm, cut perpendicular to an optic axis, stage at 45°: one melatope and an almost straight isogyre." \
    conoscope --mineral forsterite --cut optic-axis --thickness 100um --stage-deg 45 --size $size

# ---------------------------------------------------------------------------------------------------------
md "## Off-centre and flash figures" ""

figure calcite-off-centre "Off-centre figure: calcite, 30 µm, the optic axis tilted 20° from the microscope axis toward azimuth 30°; the melatope leaves the centre of the field." \
    conoscope --mineral calcite --thickness 30um --tilt-deg 20 --azimuth-deg 30 --size $size
figure quartz-flash-5deg "Flash figure: quartz, 150 µm, optic axis in the plane of the section (E–W at stage 0), stage at 5°: the broad, diffuse cross that fills the field at 0° splits and leaves it after a few degrees." \
    conoscope --mineral quartz --cut optic-normal --thickness 150um --stage-deg 5 --size $size
figure quartz-flash-45deg "The same section at 45°: the retardation falls toward the two quadrants the optic axis points into and rises in the other two, so the isochromes are hyperbolae." \
    conoscope --mineral quartz --cut optic-normal --thickness 150um --stage-deg 45 --size $size

# ---------------------------------------------------------------------------------------------------------
md "## Optical activity: quartz" "" \
   "Quartz turns the plane of polarization of light along its optic axis, 21.7°/mm at 589 nm and more at shorter" \
   "wavelengths ([theory.md](theory.md) §9). Right-handed quartz turns it clockwise for an observer looking toward" \
   "the light; left-handed quartz the other way (\`--handedness\`, [conventions.md](conventions.md))." ""

figure quartz-3mm "Quartz, 3 mm, perpendicular to the optic axis: the rotation (65° at 589 nm) colours a wider centre, and the isogyres fade further out." \
    conoscope --mineral quartz --thickness 3mm --size $size
figure quartz-2mm-mica-right "Right-handed quartz, 2 mm, with the λ/4 mica plate (slow direction NE–SW): the isochromes become a two-armed spiral." \
    conoscope --mineral quartz --thickness 2mm --plate mica --size $size
figure quartz-2mm-mica-left "The same with left-handed quartz: the spiral turns the other way, which tells the two forms apart." \
    conoscope --mineral quartz --thickness 2mm --plate mica --handedness left --size $size
figure quartz-3750um-parallel "Quartz, 3.75 mm, between parallel polars: along the axis the yellow-green near 555 nm is turned by about 90° and removed, leaving the purple of Soleil's sensitive tint at the centre." \
    conoscope --mineral quartz --thickness 3750um --analyzer-deg 0 --size $size
figure paratellurite-250um "Paratellurite (TeO₂, tetragonal, positive), 250 µm, perpendicular to the optic axis: the catalog's second optically active crystal turns the plane by 26° at 589 nm (105°/mm, about five times quartz), and its birefringence (0.16, seventeen times quartz's) packs the isochromes tight around the lit, coloured centre." \
    conoscope --mineral paratellurite --thickness 250um --size $size

# ---------------------------------------------------------------------------------------------------------
md "## Conical refraction" "" \
   "The screen behind a KGd(WO₄)₂ slab 20 mm long, cut perpendicular to an optic axis, at 633 nm" \
   "([conical.md](conical.md)). Each image is centred on the ring and normalised to its brightest pixel." ""

figure conical-wave-unpolarized "Wave optics (Belsky–Khapalyuk–Berry), Gaussian beam w = 40 µm, unpolarized, focal image plane: the bright outer ring, the dark Poggendorff ring and the fainter inner ring." \
    conical --crystal KGW --length 20mm --wavelength 633nm --size 512
figure conical-wave-linear30 "Wave optics, linear polarization at 30°: a crescent, brightest at azimuth 60° (twice the polarization angle)." \
    conical --crystal KGW --length 20mm --wavelength 633nm --polarization linear:30 --waist 20um --size 512
figure conical-ray "Ray optics: rays through a 25 µm pinhole in a 50 mm filter, each split into the crystal's two exact plane-wave modes and traced to a screen 50 mm behind the slab." \
    conical --crystal KGW --length 20mm --wavelength 633nm --mode ray --pinhole 25um --filter 50mm --screen-distance 50mm --size 512

# ---------------------------------------------------------------------------------------------------------
md "## A thin section under the turning stage" "" \
   "[thin_sections/granite](../thin_sections/granite) (quartz, orthoclase, albite, biotite, muscovite;" \
   "4.1 mm square, 30 µm) between crossed polars, with the stage at 0°, 22.5°, 45° and 67.5°, above without" \
   "and below with the gypsum plate (first-order red, slow direction NE–SW). Grains go extinct every 90°;" \
   "with the plate, quartz and feldspar grains whose slow direction lies near NE–SW climb to second-order" \
   "blue and those with it near NW–SE fall to first-order yellow." ""
stages=(0 22.5 45 67.5)
commands=()
xpl_row="|" plate_row="|" header="| |" rule="|---|"
for stage in "${stages[@]}"; do
    tag=${stage/./p}
    render "granite-xpl-${tag}deg" orthoscope --section thin_sections/granite --stage-deg "$stage"
    commands+=("$command")
    render "granite-gypsum-${tag}deg" orthoscope --section thin_sections/granite --stage-deg "$stage" --plate gypsum
    commands+=("$command")
    header+=" stage ${stage}° |"
    rule+="---|"
    xpl_row+=" ![granite, crossed polars, stage ${stage}°](gallery/granite-xpl-${tag}deg.png) |"
    plate_row+=" ![granite, gypsum plate, stage ${stage}°](gallery/granite-gypsum-${tag}deg.png) |"
done
md "$header" "$rule" "| **crossed polars** ${xpl_row}" "| **+ gypsum plate** ${plate_row}" "" '```sh' "${commands[@]}" '```' ""

# ---------------------------------------------------------------------------------------------------------
md "## The Michel-Lévy chart" ""
figure michel-levy "Interference colours against retardation (0–2000 nm) and thickness, with lines of equal birefringence, computed with the orthoscope's physics ([orthoscope.md](orthoscope.md))." \
    chart

# ---------------------------------------------------------------------------------------------------------
md "## A sweep: an off-centre figure turned about the microscope axis" ""
sweep_dir=$(mktemp -d)
sweep_command=(sweep conoscope --mineral calcite --thickness 30um --cut optic-axis --tilt-deg 20 --size 192
               --vary azimuth-deg=0:330:30 --thumbnail 160 --columns 6 --fps 4)
echo "gallery.sh: sweep" >&2
"$binary" "${sweep_command[@]}" -o "$sweep_dir/sweep" 2>/dev/null
cp "$sweep_dir/sweep/sheet.png" "$out/sweep-calcite-azimuth-sheet.png"
cp "$sweep_dir/sweep/animation.gif" "$out/sweep-calcite-azimuth.gif"
head -n 4 "$sweep_dir/sweep/measurements.csv" | cut -d, -f1,3,8,9 >"$sweep_dir/csv"
rm -rf "$sweep_dir/sweep"
md "Calcite, 30 µm, optic axis tilted 20° and turned from 0° to 330° by 30°: the contact sheet, the animation," \
   "and the first rows of \`measurements.csv\` (the melatope measured on each frame; [sweep.md](sweep.md))." "" \
   "![sweep contact sheet](gallery/sweep-calcite-azimuth-sheet.png)" "" \
   "![sweep animation](gallery/sweep-calcite-azimuth.gif)" "" '```' "$(cat "$sweep_dir/csv")" '```' "" \
   '```sh' "petroscope ${sweep_command[*]} -o sweep/" '```' ""
rm -rf "$sweep_dir"

# ---------------------------------------------------------------------------------------------------------
md "## Fitting a photo: thickness from an off-centre figure" "" \
   "The photo below stands in for a camera image: calcite, 40 µm, optic axis tilted 12° toward azimuth 30°." \
   "\`petroscope fit conoscope\` is told only the mineral and a start twice too thin (20 µm, tilt 10°," \
   "azimuth 20°); it scans the thickness over retardation orders, then fits thickness, centre, scale," \
   "rotation, tilt, white balance, black level, gamma and blur ([fitting.md](fitting.md)). Photo | best fit |" \
   "residual (×4 around grey); under it the summary the command prints." ""
render fit-calcite-photo conoscope --mineral calcite --thickness 40um --tilt-deg 12 --azimuth-deg 30 --size $size
photo_command=$command
fit_dir=$(mktemp -d)
fit_command=(fit conoscope --photo "$out/fit-calcite-photo.png" --mineral calcite --thickness 20um --tilt-deg 10
             --azimuth-deg 20 --free thickness,center,scale,rotation,tilt,white-balance,black,gamma,blur)
echo "gallery.sh: fit" >&2
if ! "$binary" "${fit_command[@]}" -o "$fit_dir" >"$fit_dir/summary.txt" 2>&1; then
    echo "gallery.sh: failed: petroscope ${fit_command[*]} -o $fit_dir" >&2
    cat "$fit_dir/summary.txt" >&2
    rm -rf "$fit_dir"
    exit 1
fi
cp "$fit_dir/side_by_side.png" "$out/fit-calcite-side-by-side.png"
md "![photo, model and residual](gallery/fit-calcite-side-by-side.png)" "" \
   '```' "$(grep -v '^wrote' "$fit_dir/summary.txt")" '```' "" \
   '```sh' "$photo_command" "petroscope ${fit_command[*]} -o fit/" '```' ""
rm -rf "$fit_dir"

chmod 644 "$page_tmp"
mv "$page_tmp" "$page"
trap - EXIT
echo "gallery.sh: wrote $page and $(ls "$out"/*.png | wc -l) images in $((SECONDS - started)) s" >&2
