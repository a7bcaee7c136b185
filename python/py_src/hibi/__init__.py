"""hibi: crack patterns from three graphics papers, as NumPy arrays.

- :class:`Mud`: Model A, a drying layer of mud as a spring lattice (Hirota et al.).
- :class:`Glass`: Model B, cracks growing in a glass plate hit by a ball (Agui et al.).
- :class:`Skin`: Model C, skin as hierarchical Voronoi cells (Ishii et al.).

Each model takes its parameters as keyword arguments named as the Rust fields, over the
paper's defaults or a named preset (``Mud("fig6b", seed=3)``); ``step(budget)`` runs a bounded
amount of work and ``run()`` runs to the end, both with the GIL released. ``render(layers)``
draws layers (``"mask"``, ``"height"``, ``"height16"``, ``"normal"``, ``"normal_rgb8"``,
``"time"``, ``"cell"``, ``"preview"``) into NumPy arrays that own the Rust buffers. Bad input
raises ``ValueError`` naming the field, and nothing is built.

:mod:`hibi.dataset` writes datasets of samples (image, crack mask, COCO polygons) in shards,
on one process, a thread pool or a Dask cluster.
"""

from ._hibi import (
    LAYERS,
    Glass,
    GlassProgress,
    Mud,
    MudProgress,
    Skin,
    SkinProgress,
    encode_png,
    presets,
)

__all__ = [
    "LAYERS",
    "Glass",
    "GlassProgress",
    "Mud",
    "MudProgress",
    "Skin",
    "SkinProgress",
    "encode_png",
    "presets",
]
__version__ = "0.1.0"
