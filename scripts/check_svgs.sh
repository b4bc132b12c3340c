#!/bin/sh
# Hand-run check (CI does not install a browser): does each SVG asperity writes render in a
# browser as gnuplot's PNG of the same figure? Usage, from the repository root after a build:
#
#   scripts/check_svgs.sh [DIR]      # default: a fresh folder under /tmp
#
# Draws every figure the project writes as SVG (the Catch2 figure tests, which keep theirs in
# DIR when ASPERITY_KEEP_FIGURES=DIR), redraws each as PNG from its kept script (the svg terminal
# swapped for pngcairo, same size and fonts), renders each SVG with headless Chromium (Debian
# package `chromium`) at that size, and compares the two per figure:
#   text   every <text> of the SVG (tspans joined) is in the figure's script (no text lost,
#          garbled or added by the SVG writer; entities decoded; tic numbers skipped);
#   blank  the browser's picture is not blank (more than 1 % of its pixels not white);
#   ink    the share of non-white pixels of the two pictures within a factor of 2 (the same
#          content drawn; Chromium's fonts and antialiasing differ from cairo's, so no pixel diff).
# Prints one line per figure (OK or what differs) and exits 1 when any differs. Results of a
# run: docs/commands.md (Figures).
set -eu
OUT=${1:-$(mktemp -d -t asperity-svgs.XXXXXX)}
BUILD=${BUILD:-build}
CHROMIUM=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$CHROMIUM" ] || { echo "check_svgs: chromium not found (apt-get install chromium)" >&2; exit 2; }
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

# 1. The figures: every writer's SVG, from the figure tests (kept in $OUT).
for suite in report studies bench; do
  ASPERITY_KEEP_FIGURES="$OUT" "$BUILD/asperity_tests_$suite" "[figures]" >/dev/null
done

# 2. The PNG twins, the browser's pictures, the comparison.
exec /usr/bin/python3 - "$OUT" "$CHROMIUM" <<'PY'
import html, pathlib, re, subprocess, sys, tempfile
import matplotlib.image as mpimg

out, chromium = pathlib.Path(sys.argv[1]), sys.argv[2]


def plain(s):  # enhanced-text markup and escapes dropped, as a reader sees the text
    s = s.replace("' . \"'\" . '", "'")  # gnuplot_quote's apostrophe: 'A(Q)' . "'" . 's'
    s = re.sub(r"'\s*\.\s*'", "", s)  # gnuplot's 'a' . 'b' string joins: one text
    return re.sub(r"[\\^_{}]", "", html.unescape(s))


def svg_texts(svg):
    found = (html.unescape(re.sub(r"<[^>]+>", "", m.group(1))).strip()
             for m in re.finditer(r"<text[^>]*>(.*?)</text>", svg, re.S))
    return [t for t in found if t]


def ink(path):  # the share of pixels that are not (near) white
    img = mpimg.imread(str(path))[..., :3].astype(float)
    return float((img.min(axis=2) < 0.9).mean())


# Each kept script (NAME.gp, a fit's plots.gp and fitted.gp) with its svg terminal swapped for
# pngcairo (same size and font) draws the PNG twin of each of its SVGs.
scripts = {}
for gp in sorted(out.rglob("*.gp")):
    if gp.name.endswith(".twin.gp"):
        continue
    script = gp.read_text()
    # pngcairo takes points at 96 per inch already: the svg terminal's fontscale (points to CSS
    # pixels) would draw its text a third larger than the browser does.
    twin = re.sub(r"^set terminal svg (.*?)(?: fontscale [0-9.]+)?$", r"set terminal pngcairo \1", script, flags=re.M)
    twin = re.sub(r"^set output '([^']*)\.svg'", r"set output '\1.twin.png'", twin, flags=re.M)
    if twin == script:
        continue
    path = gp.with_name(gp.stem + ".twin.gp")
    path.write_text(twin)
    subprocess.run(["gnuplot", path.name], cwd=gp.parent, check=True, capture_output=True)
    for name in re.findall(r"^set output '([^']*)\.svg'", script, flags=re.M):
        scripts[gp.parent / (name + ".svg")] = script

bad = 0
for svg, script in sorted(scripts.items()):
    text = svg.read_text()
    w, h = (int(float(v)) for v in re.search(r'<svg[^>]*?width="([0-9.]+)[^"]*"[^>]*?height="([0-9.]+)', text).groups())
    png = svg.with_name(svg.stem + ".twin.png")
    shot = svg.with_name(svg.stem + ".chromium.png")
    # Through an <img> of a page: Chromium 156 headless screenshots a bare SVG file blank.
    page = svg.with_name(svg.stem + ".chromium.html")
    page.write_text(f"<html><body style='margin:0;background:white'><img src='{svg.name}'></body></html>")
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={profile}",
                        "--hide-scrollbars", f"--window-size={w},{h}", f"--screenshot={shot}", page.as_uri()],
                       check=True, capture_output=True, timeout=120)
    problems = []
    missing = [t for t in svg_texts(text)
               if plain(t) not in plain(script) and not re.fullmatch(r"[-−+0-9.,x×eE ]*", plain(t))]
    if missing:
        problems.append(f"text not in the script: {missing[:3]}")
    a, b = ink(shot), ink(png)
    if a < 0.01:
        problems.append(f"browser picture blank ({a:.2%} ink)")
    elif not 0.5 < a / b < 2:
        problems.append(f"ink {a:.2%} in the browser, {b:.2%} in the PNG")
    bad += bool(problems)
    print(f"{'DIFFERS' if problems else 'OK':8} {svg.relative_to(out)}  (ink: browser {a:.2%}, png {b:.2%})"
          + "".join("\n         " + p for p in problems))
print(f"{bad} of {len(scripts)} SVGs differ from their PNG; pictures in {out} (NAME.chromium.png, NAME.twin.png)")
sys.exit(1 if bad else 0)
PY
