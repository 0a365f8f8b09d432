#!/usr/bin/env python3
"""Generate tests/data/erf_reference.csv: erf(x), erfc(x) and erfcx(x) = exp(x^2) erfc(x)
at 60 significant digits with mpmath, then rounded to the nearest f64 (repr of float()).

Run from the crate folder:  python3 tools/gen_erf_reference.py > tests/data/erf_reference.csv
(needs `pip install mpmath`; the committed file was made with mpmath 1.3.0).
"""
import mpmath

mpmath.mp.dps = 60

xs = set()
# dense grid over the whole interesting range, both signs
for i in range(-600, 601):
    xs.add(mpmath.mpf(i) / 20)  # -30 .. 30 step 0.05
# tiny arguments and the points the issue names
for e in range(-300, 0, 7):
    xs.add(mpmath.mpf(10) ** e)
    xs.add(-mpmath.mpf(10) ** e)
for v in ["0.5", "0.84375", "1.25", "2.857142857142857", "6", "-6", "26", "-26", "26.5", "27",
          "27.2", "30", "-30", "35", "50", "100", "1e3", "1e5"]:
    xs.add(mpmath.mpf(v))

print("# x,erf,erfc,erfcx  (mpmath %s, 60 digits, rounded to f64)" % mpmath.__version__)
for x in sorted(xs):
    xf = float(x)
    x = mpmath.mpf(xf)  # use the exact f64 argument
    erf = mpmath.erf(x)
    erfc = mpmath.erfc(x)
    erfcx = mpmath.exp(x * x) * erfc
    print("%r,%r,%r,%r" % (xf, float(erf), float(erfc), float(erfcx)))
