"""Post-processing: CSV writing and plots (matplotlib, Agg backend, no display needed)."""
from __future__ import annotations

import csv
from pathlib import Path


def write_csv(path, rows: list[dict]):
    """Write a list of dicts (same keys) to CSV; column names carry their units."""
    path = Path(path)
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return path


def plot_quasistatic_sweep(rows: list[dict], path, title: str = ""):
    """Four panels over inner-ring speed: contact angles, contact loads, cage speed and ratio, spin-to-roll."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = [r["speed_rpm"] for r in rows]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    ax[0, 0].plot(n, [r["alpha_i_deg"] for r in rows], label="inner")
    ax[0, 0].plot(n, [r["alpha_o_deg"] for r in rows], label="outer")
    ax[0, 0].set_ylabel("contact angle [deg]")
    ax[0, 1].plot(n, [r["Q_i_N"] for r in rows], label="inner")
    ax[0, 1].plot(n, [r["Q_o_N"] for r in rows], label="outer")
    ax[0, 1].set_ylabel("contact load, most loaded ball [N]")
    ax[1, 0].plot(n, [r["cage_speed_rpm"] for r in rows])
    ax[1, 0].set_ylabel("pure-rolling cage speed [rpm]")
    ax[1, 1].plot(n, [r["spin_roll_i"] for r in rows], label="inner")
    ax[1, 1].plot(n, [r["spin_roll_o"] for r in rows], label="outer")
    ax[1, 1].set_ylabel("spin-to-roll ratio [-]")
    for a in ax.flat:
        a.set_xlabel("inner-ring speed [rpm]")
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend()
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
