"""plot.py TABLE.tsv XCOL YCOL TITLE > plot.svg: error against time as an
SVG line plot with labelled points (log scale on y when the values span
more than a decade).  Plain Python, no plotting library needed."""
import math, sys

path, xc, yc, title = sys.argv[1:5]
rows = [l.rstrip('\n').split('\t') for l in open(path)]
head, rows = rows[0], rows[1:]
xi, yi = head.index(xc), head.index(yc)
pts = [(float(r[xi]), float(r[yi]), r[0]) for r in rows]
W, H, M = 640, 400, 70
xs = [p[0] for p in pts]
ys = [p[1] for p in pts if p[1] > 0]
logy = bool(ys) and max(ys) / min(ys) > 10
def fy(v):
    if logy:
        v = math.log10(max(v, min(ys) / 10))
        lo, hi = math.log10(min(ys) / 10), math.log10(max(ys) * 2)
    else:
        lo, hi = 0.0, max([p[1] for p in pts] + [1e-300]) * 1.1
    return H - M - (v - lo) / (hi - lo) * (H - 2 * M)
x0, x1 = 0.0, max(xs) * 1.1
def fx(v):
    return M + (v - x0) / (x1 - x0) * (W - 2 * M)
out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
       'font-family="sans-serif" font-size="12">' % (W, H),
       '<rect width="100%" height="100%" fill="white"/>',
       '<text x="%d" y="24" font-size="14">%s</text>' % (M, title),
       '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (M, H - M, W - M, H - M),
       '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (M, M, M, H - M),
       '<text x="%d" y="%d">%s (s)</text>' % (W // 2, H - 25, xc),
       '<text x="12" y="%d" transform="rotate(-90 12 %d)">%s%s</text>'
       % (H // 2, H // 2, yc, ' (log)' if logy else '')]
for k in range(6):
    v = x0 + (x1 - x0) * k / 5
    out.append('<text x="%.1f" y="%d" text-anchor="middle">%.3g</text>' % (fx(v), H - M + 16, v))
if logy:
    lo, hi = math.floor(math.log10(min(ys) / 10)), math.ceil(math.log10(max(ys) * 2))
    for k in range(int(lo), int(hi) + 1):
        v = 10.0 ** k
        if min(ys) / 10 <= v <= max(ys) * 2:
            out.append('<text x="%d" y="%.1f" text-anchor="end">1e%d</text>' % (M - 6, fy(v) + 4, k))
else:
    top = max([p[1] for p in pts] + [1e-300]) * 1.1
    for k in range(6):
        v = top * k / 5
        out.append('<text x="%d" y="%.1f" text-anchor="end">%.3g</text>' % (M - 6, fy(v) + 4, v))
prev = None
for x, y, lab in sorted(pts):
    px, py = fx(x), fy(y) if (y > 0 or not logy) else fy(min(ys) / 10)
    if prev:
        out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#36c"/>' % (prev + (px, py)))
    out.append('<circle cx="%.1f" cy="%.1f" r="4" fill="#36c"/>' % (px, py))
    out.append('<text x="%.1f" y="%.1f">%s: %.3g</text>' % (px + 6, py - 6, lab, y))
    prev = (px, py)
out.append('</svg>')
print('\n'.join(out))
