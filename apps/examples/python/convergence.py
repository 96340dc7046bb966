"""Sod's shock tube at four resolutions: L1 density error against zones and run time (docs/python.md).
Usage: convergence.py [FIGURE.png]   (without a file name the plot is shown)"""
import pathlib, sys, time
import matplotlib
matplotlib.use("Agg" if len(sys.argv) > 1 else matplotlib.get_backend())
import matplotlib.pyplot as plt
import stagger

sod = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "sod.toml"
rows = []
for refine in [1, 2, 4, 8]:
    sim = stagger.Simulation(stagger.load_scene(sod, {"mesh.refine": refine}))
    start = time.perf_counter()
    sim.run()
    rows.append((sim.scene.zones, time.perf_counter() - start, sim.errors()["L1_density"], sim.cycle))
print("| zones | cycles | run time (s) | L1 density error |\n|---:|---:|---:|---:|")
for zones, seconds, error, cycles in rows:
    print(f"| {zones} | {cycles} | {seconds:.3f} | {error:.4e} |")
zones, seconds, errors, _ = zip(*rows)
figure, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
left.loglog(zones, errors, "o-"), left.set(xlabel="zones", ylabel="L1 density error", title="convergence")
left.xaxis.set_minor_locator(matplotlib.ticker.NullLocator()), left.set_xticks(zones, [str(z) for z in zones])
right.loglog(seconds, errors, "o-"), right.set(xlabel="run time (s)", title="work against precision")
figure.savefig(sys.argv[1], dpi=120) if len(sys.argv) > 1 else plt.show()
