"""Type stubs of hibi's extension module (the classes :mod:`hibi` exports)."""

from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

LayerName = Literal["mask", "height", "height16", "normal", "normal_rgb8", "time", "cell", "preview"]
LAYERS: List[str]

class MudProgress:
    """Where a drying-mud run stands."""

    shrink: float
    time: float
    broken_springs: int
    crack_density: float
    finished: bool
    work: int

class GlassProgress:
    """Where a plate stands."""

    time: int
    cracks: int
    growing: int
    vertices: int
    finished: bool
    capacity_reached: bool
    work: int

class SkinProgress:
    """Where a skin's build stands."""

    cells: int
    roots: int
    root_total: int
    finished: bool
    capacity_reached: bool
    work: int

class Mud:
    """Model A (Hirota et al.): a drying layer of mud as a spring lattice.

    Keywords are ``hibi_core::mud::MudParams``'s fields over the preset's (or the paper's
    defaults): topology ("square", "hexagonal", "irregular"), boundary ("open", "periodic"),
    solver ("explicit", "quasi-static"), drive ("shrink", "growth"), columns, rows, seed,
    layer_thickness, element_size, long_step, short_step, shrink_ratio,
    displacement_tolerance, damping_factor, density, young_modulus, shear_modulus,
    break_stretch_mean, break_stretch_spread, break_stretch_size_exponent,
    anisotropy_direction (radians), anisotropy_ratio, stiffness_anisotropy_ratio,
    target_shrink, target_crack_density. A bad value raises ``ValueError`` naming the field.
    """

    def __init__(
        self,
        preset: Optional[str] = None,
        *,
        topology: str = ...,
        boundary: str = ...,
        solver: str = ...,
        drive: str = ...,
        columns: int = ...,
        rows: int = ...,
        seed: int = ...,
        layer_thickness: float = ...,
        element_size: float = ...,
        long_step: float = ...,
        short_step: float = ...,
        shrink_ratio: float = ...,
        displacement_tolerance: float = ...,
        damping_factor: float = ...,
        density: float = ...,
        young_modulus: float = ...,
        shear_modulus: float = ...,
        break_stretch_mean: float = ...,
        break_stretch_spread: float = ...,
        break_stretch_size_exponent: float = ...,
        anisotropy_direction: float = ...,
        anisotropy_ratio: float = ...,
        stiffness_anisotropy_ratio: float = ...,
        target_shrink: float = ...,
        target_crack_density: float = ...,
    ) -> None: ...
    def step(self, budget: int) -> MudProgress:
        """Runs for at most about ``budget`` units of work (GIL released)."""
    def run(self, callback: Optional[Callable[[MudProgress], Any]] = None, budget: int = 2_000_000) -> MudProgress:
        """Runs to the end (GIL released); with ``callback``, in steps of ``budget`` units."""
    @property
    def progress(self) -> MudProgress: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @property
    def extent(self) -> Tuple[float, float]:
        """Width and height of the domain (one period when periodic), lattice units."""
    def statistics(self) -> Dict[str, float]: ...
    def segments(self) -> npt.NDArray[np.float32]:
        """(n, 8): start x, y, end x, y, width at each end, break time at each end."""
    def network(self) -> Dict[str, npt.NDArray[Any]]:
        """vertices, degree, on_border, from, to, offsets, points, width, time."""
    def cells(self) -> Dict[str, Any]:
        """points (lattice units), offsets, area (holes negative), hole_of, wrapping."""
    @overload
    def render(
        self,
        layers: Optional[str] = None,
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        width_scale: Optional[float] = None,
        min_width: Optional[float] = None,
        groove_depth: Optional[float] = None,
        offset: Optional[Tuple[float, float]] = None,
        bump: Optional[float] = None,
        until: Optional[float] = None,
        threads: int = 1,
    ) -> npt.NDArray[Any]: ...
    @overload
    def render(
        self,
        layers: Sequence[str],
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        width_scale: Optional[float] = None,
        min_width: Optional[float] = None,
        groove_depth: Optional[float] = None,
        offset: Optional[Tuple[float, float]] = None,
        bump: Optional[float] = None,
        until: Optional[float] = None,
        threads: int = 1,
    ) -> Dict[str, npt.NDArray[Any]]: ...
    @staticmethod
    def presets() -> Tuple[str, ...]: ...

class Glass:
    """Model B (Agui et al.): cracks growing in a glass plate hit by a ball.

    Keywords are ``hibi_core::glass::GlassParams``'s fields over the preset's (or the paper's
    defaults): width, height, impact (x, y), seed, radial_mean, ring_threshold, large_slope,
    large_offset, ring_slope, ring_offset, ring_radius_slope, ring_radius_offset, large_speed,
    radial_speed, ring_speed, spread_ratio, spread ("normal", "uniform"), turn_limit (radians),
    turn_delay, sector_angle (radians), sector_radius, tip_repulsion, crack_attraction, wander
    (radians), ring_adherence, max_cracks, max_vertices. A plate resized without ``impact``
    is hit at its centre.
    """

    def __init__(
        self,
        preset: Optional[str] = None,
        *,
        width: float = ...,
        height: float = ...,
        impact: Tuple[float, float] = ...,
        seed: int = ...,
        radial_mean: float = ...,
        ring_threshold: float = ...,
        large_slope: float = ...,
        large_offset: float = ...,
        ring_slope: float = ...,
        ring_offset: float = ...,
        ring_radius_slope: float = ...,
        ring_radius_offset: float = ...,
        large_speed: float = ...,
        radial_speed: float = ...,
        ring_speed: float = ...,
        spread_ratio: float = ...,
        spread: str = ...,
        turn_limit: float = ...,
        turn_delay: float = ...,
        sector_angle: float = ...,
        sector_radius: float = ...,
        tip_repulsion: float = ...,
        crack_attraction: float = ...,
        wander: float = ...,
        ring_adherence: float = ...,
        max_cracks: int = ...,
        max_vertices: int = ...,
    ) -> None: ...
    def step(self, budget: int) -> GlassProgress: ...
    def run(self, callback: Optional[Callable[[GlassProgress], Any]] = None, budget: int = 100_000) -> GlassProgress: ...
    def impact(self, at: Tuple[float, float]) -> Dict[str, int]: ...
    @property
    def impact_counts(self) -> Dict[str, int]: ...
    @property
    def progress(self) -> GlassProgress: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    def cracks(self) -> Dict[str, npt.NDArray[Any]]:
        """points (px), time, offsets, end, kind, impact."""
    def fragments(self) -> Dict[str, npt.NDArray[Any]]:
        """points (px), offsets, area (px², holes negative), hole_of."""
    @overload
    def render(
        self,
        layers: Optional[str] = None,
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        line_width: Optional[float] = None,
        bump: Optional[float] = None,
        until: Optional[float] = None,
        threads: int = 1,
    ) -> npt.NDArray[Any]: ...
    @overload
    def render(
        self,
        layers: Sequence[str],
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        line_width: Optional[float] = None,
        bump: Optional[float] = None,
        until: Optional[float] = None,
        threads: int = 1,
    ) -> Dict[str, npt.NDArray[Any]]: ...
    @staticmethod
    def presets() -> Tuple[str, ...]: ...

class Skin:
    """Model C (Ishii et al.): skin as hierarchical Voronoi cells.

    Keywords are ``hibi_core::skin::SkinParams``'s fields over the preset's (or the paper's
    defaults): width, height, seed, layout ("triangular", "square", "random"), jitter
    ("normal", "uniform"), jitter_ratio, periodic, levels, and level: a list of dicts, one per
    level from the coarsest, with spacing, perturbation, perturbation_decay,
    perturbation_depth, stretch (x, y), profile (3k + 1 points (x', z)) and roundness.
    """

    def __init__(
        self,
        preset: Optional[str] = None,
        *,
        width: int = ...,
        height: int = ...,
        seed: int = ...,
        layout: str = ...,
        jitter: str = ...,
        jitter_ratio: float = ...,
        periodic: bool = ...,
        levels: int = ...,
        level: List[Dict[str, Any]] = ...,
    ) -> None: ...
    def step(self, budget: int) -> SkinProgress: ...
    def run(self, callback: Optional[Callable[[SkinProgress], Any]] = None, budget: int = 1_000_000) -> SkinProgress: ...
    @property
    def progress(self) -> SkinProgress: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    def cells(self) -> Dict[str, Any]:
        """points (px), fixed, offsets, level, parent, site, centre, fixed_point_bits."""
    @overload
    def render(
        self,
        layers: Optional[str] = None,
        *,
        cell_level: int = 0,
        light: Optional[Sequence[float]] = None,
        ridge: Optional[Sequence[float]] = None,
        furrow: Optional[Sequence[float]] = None,
        ambient: Optional[float] = None,
        specular: Optional[float] = None,
        threads: int = 1,
    ) -> npt.NDArray[Any]: ...
    @overload
    def render(
        self,
        layers: Sequence[str],
        *,
        cell_level: int = 0,
        light: Optional[Sequence[float]] = None,
        ridge: Optional[Sequence[float]] = None,
        furrow: Optional[Sequence[float]] = None,
        ambient: Optional[float] = None,
        specular: Optional[float] = None,
        threads: int = 1,
    ) -> Dict[str, npt.NDArray[Any]]: ...
    @staticmethod
    def presets() -> Tuple[str, ...]: ...

def encode_png(image: npt.NDArray[Union[np.uint8, np.uint16]]) -> bytes:
    """PNG bytes of a uint8 (h, w), (h, w, 3), (h, w, 4) or uint16 (h, w) image."""

def presets() -> Dict[str, List[str]]: ...
