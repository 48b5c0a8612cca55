# %% [markdown]
# # The measurement loop in Python
#
# The README's measurement loop (docs/measurement-loop.md: synth → compare → diagnose →
# calibrate → fly) in a notebook,
# on the shipped paper world (`configs/synth/paper_world.toml`): a synthetic session of three
# shafts whose hidden physics (added effective clubhead mass per shaft, a ball offset) we
# pretend not to know. Cells are `# %%` blocks (VS Code, Jupyter with jupytext, Spyder); the
# file also runs as a script.
#
# Run from the repository root after `pip install .` and `pip install matplotlib tqdm`:
#
#     python examples/python/measurement_loop.py
#
# Units are the shots file's: mph, degrees, rpm, mm; flight distances in yards.

# %%
import os
import sys
from pathlib import Path

import matplotlib

if not os.environ.get("DISPLAY") and "ipykernel" not in sys.modules:
    matplotlib.use("Agg")  # a script without a screen: the figures go to files
import matplotlib.pyplot as plt
import numpy as np

import smash_golf as sg

ROOT = Path.cwd()
OUT = Path(os.environ.get("SMASH_EXAMPLE_OUT", "."))
club = sg.Club.load(ROOT / "configs" / "clubs" / "paper_driver.toml")
shots, truth = sg.synth(ROOT / "configs" / "synth" / "paper_world.toml")
print(club, f"{len(shots)} shots, groups {sorted(shots['group'].unique())}")

# %% [markdown]
# ## 1. The nominal club against the measurements
# `predict` adds `pred_*` and `err_*` (= predicted − measured) columns.

# %%
pred = sg.predict(club, shots)
errors = [c for c in pred.columns if c.startswith("err_")]
print(pred.groupby("group")[errors].agg(["mean", "std"]).round(2).T)

# %% [markdown]
# `compare` is the CLI's diagnosis of the errors: Table 2, which biases are significant, face
# maps, trends and ranked findings with hints.

# %%
report = sg.compare(club, shots)
print(report["text"])

# %% [markdown]
# ## 2. Which physics is missing?
# `diagnose` ranks every library effect by how much it explains, cross-validated by golfer, and
# selects them forward until the gain is not significant. A tqdm bar shows its fits.

# %%
d = sg.diagnose(club, shots)
print("selected:", d["selected"])
print("calibrate with:", d["calibrate_flags"])
print(d["estimates"][["effect", "param", "group", "value", "stderr", "unit", "status"]])
print("--- the world's hidden physics ---")
print(truth)

# %% [markdown]
# ## 3. Calibrate the selected effects and watch the error fall
# Under the measurement model diagnose chose (impact-location and delivery noise), as its
# `calibrate_flags` say.

# %%
# The CLI's `calibrate_flags`: the selected effects and the measurement model diagnose chose.
flags = dict(zip(*[iter(d["calibrate_flags"].split())] * 2))
impact_noise = flags.get("--impact-noise-mm")
cal = sg.calibrate(
    club,
    shots,
    flags.get("--effects", ""),
    impact_noise_mm=tuple(map(float, impact_noise.split(","))) if impact_noise else None,
    delivery_noise=flags.get("--delivery-noise"),
)
print(cal["params"][["effect", "param", "group", "value", "stderr", "unit"]])
print(f"chi2: nominal {cal['chi2_nominal']:.1f} -> calibrated {cal['chi2']:.1f}")
calibrated = cal["club"]
after = sg.predict(calibrated, shots)

fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=False)
for ax, col, unit in [
    (axes[0], "err_ball_speed_mph", "mph"),
    (axes[1], "err_backspin_rpm", "rpm"),
]:
    bins = np.histogram_bin_edges(np.r_[pred[col], after[col]], bins=40)
    ax.hist(pred[col], bins=bins, alpha=0.6, label="nominal club")
    ax.hist(after[col], bins=bins, alpha=0.6, label="calibrated club")
    ax.axvline(0, color="k", lw=0.8)
    ax.set_xlabel(f"{col} ({unit})")
    ax.set_ylabel("shots")
    ax.legend()
fig.suptitle("Model − measured, paper world")
fig.tight_layout()
fig.savefig(OUT / "measurement_loop_errors.png", dpi=120)

# %% [markdown]
# ## 4. What it means in yards
# Fly the measured launch and both models' predicted launch in the same air.

# %%
air = dict(temperature_c=25.0, elevation_m=300.0)
measured = sg.flight(shots, **air)
nominal_flight = sg.flight(pred, columns="predicted", **air)
calibrated_flight = sg.flight(after, columns="predicted", **air)
carry_error = {
    "nominal": nominal_flight["pred_carry_yd"] - measured["pred_carry_yd"],
    "calibrated": calibrated_flight["pred_carry_yd"] - measured["pred_carry_yd"],
}
for name, e in carry_error.items():
    print(f"carry error, {name} club: mean {e.mean():+.2f} yd, sd {e.std():.2f} yd")

fig, ax = plt.subplots(figsize=(6, 4))
ax.scatter(measured["pred_carry_yd"], carry_error["nominal"], s=6, label="nominal club")
ax.scatter(measured["pred_carry_yd"], carry_error["calibrated"], s=6, label="calibrated club")
ax.axhline(0, color="k", lw=0.8)
ax.set_xlabel("carry of the measured launch (yd)")
ax.set_ylabel("model − measured carry (yd)")
ax.legend()
fig.tight_layout()
fig.savefig(OUT / "measurement_loop_carry.png", dpi=120)

# %% [markdown]
# ## 5. Variants in a loop
# A `Club` is a value: build variants and predict them, here an added effective clubhead mass
# for shaft A swept on the calibrated club (the truth file shows what the world hid).

# %%
a_shots = shots[shots["group"] == "A"]
masses_g = np.linspace(0.0, 5.0, 11)
bias_mph = []
for dm_g in masses_g:
    variant = calibrated.with_effect("added_mass", group="A", dm_g=float(dm_g))
    bias_mph.append(sg.predict(variant, a_shots)["err_ball_speed_mph"].mean())
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(masses_g, bias_mph, marker="o")
ax.axhline(0, color="k", lw=0.8)
ax.set_xlabel("added effective clubhead mass, shaft A (g)")
ax.set_ylabel("mean ball-speed error (mph)")
fig.tight_layout()
fig.savefig(OUT / "measurement_loop_added_mass.png", dpi=120)
plt.show()
