"""Fit the laws to a laboratory creep curve and plot the fits.

Sample run (from the repository root, after `bash scripts/build.sh`):
    PYTHONPATH=build/python /usr/bin/python3 examples/python/fit_lab_curve.py [OUT.png]

Reads examples/creep-data/steps-unloading.csv (a synthetic multi-stage shear creep
test: 0.232 MPa, 0.424 MPa from 100 h, unloaded at 200 h; column `tau` holds the
stress), fits every law (`rheodda fit ... --law all --stress-column tau`), prints
the ranking by BIC with each law's parameters and standard errors, the YAML block
of the best law, and draws the data, the fitted curves and their residuals into
OUT.png (default docs/img/python-fit.png).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rheodda  # noqa: E402

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "img", "python-fit.png")
data_path = os.path.join("examples", "creep-data", "steps-unloading.csv")

ranked, skipped = rheodda.fit_all(os.path.join(root, data_path), stress_column="tau", rank_by="bic")
print("laws ranked by BIC on {} ({} points):".format(data_path, ranked[0].points))
for r in ranked:
    params = ", ".join("{} = {:.5g} {}".format(n, r.values[n], "+- {:.2g}".format(r.errors[n])
                                               if r.identifiable[n] else "(not identifiable)") for n in r.names)
    print("  {:<20} BIC {:9.2f}  RMSE {:.3g} mm  {}".format(r.law, r.bic, r.rmse, params))
for s in skipped:
    print("  skipped: " + s)
print()
print(ranked[0].yaml.replace(os.path.join(root, ""), ""))

data = ranked[0].data
fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
top.plot(data.t, data.displacement, ".", color="0.6", markersize=3, label="data ({})".format(data_path))
# the fitted laws on a fine grid (the exact response to the staged stress)
t = np.linspace(0.0, data.t[-1], 1201)
for r in ranked:
    curve = rheodda.exact_displacement(r.make_law(), data.stress, t)
    top.plot(t, curve, label="{} (BIC {:.0f})".format(r.law, r.bic))
    bottom.plot(data.t, 1e3 * (data.displacement - r.fitted), ".", markersize=2, label=r.law)
bottom.set_ylim(-0.5, 0.5)  # the three best laws: the noise; Maxwell and Kelvin leave the frame
top.set_ylabel("shear displacement [mm]")
top.set_title("Fits of a staged creep test (stress {})".format(
    ", ".join("{:g} MPa from {:g} h".format(v, s) for s, v in data.stress)), fontsize=10)
top.legend(fontsize=8)
bottom.set_xlabel("time [h]")
bottom.set_ylabel("residual [um]")
bottom.axhline(0.0, color="k", linewidth=0.5)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote " + os.path.relpath(out, root))
