"""Drawings of the corner from its specimen description: the blocks in place (course,
role), or moved by a mechanism (the LP's virtual velocities, or the DEM's final
positions), from outside the corner and from the paper's two viewpoints (a camera
square to each wall's outer face, as its Figs. 6 and 13)."""

import numpy as np

#: name: (elevation, azimuth) of matplotlib's 3-D camera, in degrees.
VIEWS = {"corner": (22, -135), "WX": (8, -90), "WY": (8, 180)}
COLOURS = {"base": "#9e9e9e", "end": "#4a4a4a", "": "#d9c7a7", "moving": "#d0473c"}


def box_faces(corners):
    """The 6 faces of a box given its 8 corners in the order of `corners_of`."""
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [[corners[k] for k in face] for face in idx]


def corners_of(block):
    """The 8 corners (m), x slowest, z fastest."""
    return np.array([[x, y, z] for x in (block.lo[0], block.hi[0]) for y in (block.lo[1], block.hi[1])
                     for z in (block.lo[2], block.hi[2])])


def moved(block, velocity, scale):
    """The corners after the small rigid motion scale * (v + omega x r)."""
    c = corners_of(block)
    return c + scale * (velocity[:3] + np.cross(velocity[3:], c - block.centroid))


def draw(ax, blocks, corners=None, moving=(), view="corner", title="", fixed=None):
    """Blocks on a 3-D axes; corners[i] overrides block i's (8, 3) corners; `moving` are
    coloured red, fixed blocks (fixed[i], default: every base and end block) grey by role."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    moving = set(moving)
    polys, colours = [], []
    for i, b in enumerate(blocks):
        pts = corners_of(b) if corners is None else corners[i]
        held = bool(b.role) if fixed is None else fixed[i]
        colour = COLOURS["moving"] if i in moving else COLOURS[b.role if held else ""]
        for face in box_faces(pts):
            polys.append(face)
            colours.append(colour)
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="k", linewidths=0.3))
    every = np.concatenate([corners_of(b) for b in blocks])
    lo, hi = every.min(axis=0), every.max(axis=0)
    span = (hi - lo).max()
    for setter, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        mid = (a + b) / 2
        setter(mid - span / 2, mid + span / 2)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(*VIEWS[view])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title(title, fontsize=9)


def figure(blocks, out, corners=None, moving=(), views=("corner", "WX", "WY"), title="", fixed=None):
    """One PNG with a panel per view (see `draw`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(4.2 * len(views), 4.4))
    for k, view in enumerate(views):
        ax = fig.add_subplot(1, len(views), k + 1, projection="3d")
        draw(ax, blocks, corners, moving, view, f"{title} - view {view}" if title else f"view {view}", fixed)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def mechanism_corners(blocks, velocity, amplitude):
    """Every block's corners moved by the mechanism, scaled so the fastest corner moves
    `amplitude` (m)."""
    fastest = max(np.abs(moved(b, velocity[i], 1.0) - corners_of(b)).max() for i, b in enumerate(blocks))
    scale = amplitude / fastest if fastest > 0 else 0.0
    return [moved(b, velocity[i], scale) for i, b in enumerate(blocks)]
