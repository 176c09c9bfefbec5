"""Plot out/moment_rotation.csv (from `cargo run --release --example moment_rotation`)."""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
data = np.genfromtxt(out / "moment_rotation.csv", delimiter=",", names=True)
x = data["theta_over_alpha"]
fig, ax = plt.subplots(figsize=(8, 5))
colors = {"solidRectangle": "C0", "hollowRectangle": "C1", "solidCircle": "C2", "hollowCircle": "C3"}
styles = {"rigid": ":", "elastic": "--", "fm05MPa": "-"}
for name in data.dtype.names[1:]:
    shape, law = name.split("_", 1)
    ax.plot(x, data[name], styles.get(law, "-"), color=colors[shape], label=f"{shape}, {law.replace('fm05MPa', 'fm = 0.5 MPa')}")
ax.axhline(0, color="k", lw=0.5)
ax.set_xlabel(r"$\theta/\alpha$")
ax.set_ylabel(r"$M_R / (W R_0 \sin\alpha)$")
ax.set_title("Four bases, same R0 and alpha, kn = 340 MPa/m")
ax.set_ylim(-0.2, 1.05)
ax.legend(fontsize=7, ncol=2)
fig.tight_layout()
fig.savefig(out / "moment_rotation.png", dpi=120)
print(f"wrote {out / 'moment_rotation.png'}")
