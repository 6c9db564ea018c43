"""The figure docs/img/shear_ratio_6.35mm_160kPa.png, end to end from Python.

    python3 docs/examples/shear_ratio.py [OUT]      (about 30 s on two cores)

Runs the default experiment (the paper's 6.35 mm glass beads under 160 kPa,
assets/scenes/shear_box.toml) through `import simsols`, prints what the
figure shows from the returned rows and summary, and leaves the run's
outputs in OUT (default results/python_shear): OUT/shear_ratio.png is the
figure.
"""
import os
import sys

import numpy as np

import simsols

here = os.path.dirname(os.path.abspath(__file__))
out = sys.argv[1] if len(sys.argv) > 1 else "results/python_shear"
scene = simsols.load_scene(os.path.join(here, "..", "..", "assets", "scenes", "shear_box.toml"))
r = simsols.run_test(scene, out, quiet=False)
rows, s = r["rows"], r["summary"]
x, ratio = rows["displacement_mm"], rows["tau_over_sigma"]
print(f"{r['steps']} steps, {len(x)} rows to {x[-1]:.2f} mm")
print(f"peak tau/sigma {s['peak_tau_over_sigma']:.3f} (phi {s['peak_friction_angle_deg']:.1f} deg) "
      f"at {s['peak_displacement_mm']:.2f} mm")
print(f"largest {np.max(ratio):.3f} at {x[np.argmax(ratio)]:.2f} mm; "
      f"residual {s['residual_tau_over_sigma']:.3f} (phi {s['residual_friction_angle_deg']:.1f} deg)")
print(f"the figure: {os.path.join(out, 'shear_ratio.png')}")
