"""The frames of a moving base, drawn: `python docs/figures/base_frames.py` writes
docs/figures/base_frames.png.

The global frame O-i0 j0 k0; the base axes R at O_b = r_b; the hub frame at theta = 0, R R_h,
at O = r_b + R p_h (hub.position p_h, hub.orientation R_h); the hub frame at theta,
R R_h A_h(theta), turned about -j_h; and a beam on it along i_h (azimuth 0, radius R). The
rotations are composed here with scipy, as docs/base.md writes them.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

OUT = Path(__file__).resolve().parent

R_BASE = Rotation.from_rotvec([0.15, 0.55, 0.25]).as_matrix()  # base.initial.rotation (rad)
R_B = np.array([2.2, 0.6, 1.0])  # O_b (m)
P_H = np.array([0.0, 1.1, 0.0])  # hub.position (m, base axes)
R_H = Rotation.from_rotvec(np.radians([0.0, 0.0, 20.0])).as_matrix()  # hub.orientation (deg)
THETA = np.radians(40.0)
RADIUS, LENGTH = 0.3, 1.8


def hub_turn(theta: float) -> np.ndarray:
    """A_h(theta): theta turns the hub about -j (docs/conventions.md)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def axes(ax, origin, R, labels, color, length=0.6, style="-"):
    for k in range(3):
        tip = origin + length * R[:, k]
        ax.plot(*np.column_stack([origin, tip]), style, color=color, lw=2)
        ax.text(*(origin + 1.12 * length * R[:, k]), labels[k], color=color, fontsize=10)


def box(ax, centre, R, size, color):
    half = 0.5 * np.asarray(size)
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    world = centre + corners @ R.T
    for i in range(8):
        for j in range(i + 1, 8):
            if np.sum(corners[i] != corners[j]) == 1:
                ax.plot(*np.column_stack([world[i], world[j]]), color=color, lw=0.8, alpha=0.6)


def main():
    fig = plt.figure(figsize=(8, 7))
    ax = fig.add_subplot(projection="3d")
    # matplotlib's z is up: draw (x, y, z) as (x, z, y) so that j0 points up on the page
    swap = np.array([[1.0, 0, 0], [0, 0, 1.0], [0, 1.0, 0]])
    view = lambda v: swap @ v  # noqa: E731
    view_R = lambda R: swap @ R  # noqa: E731

    axes(ax, view(np.zeros(3)), view_R(np.eye(3)), ("i0", "j0", "k0"), "black", 0.8)
    ax.text(*view(np.zeros(3)) - 0.15, "O", color="black")
    axes(ax, view(R_B), view_R(R_BASE), ("x_b", "y_b", "z_b"), "tab:blue", 0.7)
    ax.text(*(view(R_B) + np.array([-0.5, 0.0, -0.35])), "O_b = r_b", color="tab:blue")
    box(ax, view(R_B), view_R(R_BASE), (1.0, 0.8, 0.9), "tab:blue")
    O = R_B + R_BASE @ P_H
    shaft = R_BASE @ R_H
    axes(ax, view(O), view_R(shaft), ("", "", ""), "tab:green", 0.8, ":")
    hub = shaft @ hub_turn(THETA)
    axes(ax, view(O), view_R(hub), ("i_h", "", "k_h"), "tab:green", 0.8)
    j_h = hub[:, 1]
    ax.plot(*np.column_stack([view(O - 0.5 * j_h), view(O + 1.5 * j_h)]), "--", color="tab:green", lw=1)
    ax.text(*view(O + 1.6 * j_h), "j_h = R R_h j0", color="tab:green")
    ax.text(*(view(O) + np.array([-1.3, 0.0, 0.0])), "O = r_b + R p_h", color="tab:green", fontsize=9)
    root, tip = O + RADIUS * hub[:, 0], O + (RADIUS + LENGTH) * hub[:, 0]
    ax.plot(*np.column_stack([view(root), view(tip)]), color="tab:orange", lw=5, solid_capstyle="butt")
    ax.text(*view(tip + 0.1 * hub[:, 0]), "beam (azimuth 0)", color="tab:orange")
    arc = np.array([O + 0.6 * (shaft @ hub_turn(a))[:, 0] for a in np.linspace(0.0, THETA, 20)])
    ax.plot(*view(arc.T), color="tab:red", lw=1.5)
    ax.text(*view(arc[len(arc) // 2] - 0.25 * j_h), "theta", color="tab:red")
    ax.set_xlim(0.0, 4.0)
    ax.set_ylim(-0.2, 2.6)
    ax.set_zlim(0.0, 3.6)
    ax.set_box_aspect((4.0, 2.8, 3.6))
    ax.set_axis_off()
    ax.view_init(elev=18, azim=-62)
    ax.set_title("global O-i0 j0 k0  →  base R, r_b  →  hub at theta = 0: R R_h (dotted)\n"
                 "→  hub R R_h A_h(theta) (solid), its axis j_h  →  the beams on it", fontsize=10)
    fig.tight_layout()
    fig.savefig(OUT / "base_frames.png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
