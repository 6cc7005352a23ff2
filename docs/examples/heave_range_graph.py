# %% [markdown]
# # The heave benchmark's range graph, from Python
#
# A notebook in the "percent" format (each `# %%` is a cell: VS Code, Jupyter with jupytext, or
# plain `python docs/examples/heave_range_graph.py` from the repository's root). It needs the
# package (`pip install ./python`) and, for the picture, matplotlib.

# %%
import catena

run = catena.run("cases/benchmarks/scr-heave.toml")          # statics + 100 s of heave, ~0.4 s
arc = run["arc"]                                              # m from the top
rng = run["ranges/bending_moment/max"] - run["ranges/bending_moment/min"]  # N·m, over t >= envelope_start
i = rng.argmax()
print(f"largest moment range {rng[i] / 1e3:.2f} kN·m at {arc[i]:.1f} m; "
      f"touchdown point {run.summary['touchdown_arc_min']:.1f}–{run.summary['touchdown_arc_max']:.1f} m")

# %%
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(arc, run["ranges/bending_moment/max"] / 1e3, label="maximum")
ax.plot(arc, run["ranges/bending_moment/mean"] / 1e3, color="0.4", label="mean")
ax.plot(arc, run["ranges/bending_moment/min"] / 1e3, label="minimum")
ax.plot(arc, rng / 1e3, "k", label="range")
ax.axvspan(run.summary["touchdown_arc_min"], run.summary["touchdown_arc_max"], color="0.85",
           label="touchdown point visits")
ax.set_xlim(1000, 1400)
ax.set_xlabel("arc length from the top (m)")
ax.set_ylabel("bending moment (kN·m, negative = sag)")
ax.set_title("heave benchmark: moment envelopes from t = 50 s")
ax.legend()
fig.savefig("heave_range_graph.png", dpi=100, bbox_inches="tight")
