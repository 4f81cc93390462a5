"""Exact shadow-volume certification, the exact shadow image and the GL methods against it (docs/python.md)."""
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

NO_HIT: int
UNDEFINED_COUNT: int

ArrayLike = Union[npt.ArrayLike, np.ndarray]

def read_soup(path: str) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.uint32]]:
    """Reads a mesh file (.obj .off .ply .stl): vertices float64 (n, 3), triangles uint32 (m, 3).
    Raises ValueError with the reader's message on bad input."""
    ...

def read_scene(path: str) -> dict[str, Any]:
    """A scene (.json) or a mesh file as `shadowcert certify` reads it: vertices, triangles, casts
    (uint8 per triangle), caster_vertices, caster_triangles, lights (k, 4) and camera (a dict)."""
    ...

def certify(
    vertices: ArrayLike,
    triangles: ArrayLike,
    light: Sequence[float],
    method: str = "all",
    precision: str = "float",
    samples: int = 2000,
    seed: int = 1,
    points: Optional[ArrayLike] = None,
) -> dict[str, Any]:
    """The certificates of `shadowcert certify --json`, as a dict with the same keys ('input' is None).
    Raises ValueError on a bad array, light, method or precision."""
    ...

def exact_image(
    vertices: ArrayLike,
    triangles: ArrayLike,
    lights: ArrayLike,
    camera: Optional[Mapping[str, Any]] = None,
    *,
    eye: Optional[Sequence[float]] = None,
    target: Optional[Sequence[float]] = None,
    size: Optional[Sequence[int]] = None,
    casts: Optional[ArrayLike] = None,
    footprints: bool = True,
) -> dict[str, Any]:
    """The exact image for each light: counts uint32 (k, h, w), lit uint8 (k, h, w), ambiguity
    uint8 (k, h, w), hit_triangles uint32 (h, w), view_ambiguity uint8 (h, w), seconds float.
    Raises ValueError on bad input."""
    ...

def render(
    scene: str,
    method: str = "cpu",
    *,
    size: Optional[Tuple[int, int]] = None,
    stencil: str = "zfail",
    device: Optional[int] = None,
) -> dict[str, Any]:
    """One frame of a GL method, headless through EGL, as `shadowcert render --method M` draws it:
    image uint8 (h, w, 4), lit uint8 (h, w), counts uint8 (h, w) or None (the shadow maps),
    stencil (per light), method, renderer. Raises ValueError on a bad file or argument,
    RuntimeError when no GL 4.5 context can be made."""
    ...

def diff(
    scene: str,
    methods: Sequence[str] = ("cpu", "cs", "gs", "ts", "pertri"),
    *,
    size: Optional[Tuple[int, int]] = None,
    stencil: str = "zfail",
    device: Optional[int] = None,
) -> dict[str, dict[str, Any]]:
    """Each GL method against the exact image, as `shadowcert diff --json` compares them: by
    method name, robust, hard_errors, ambiguous, agree, coverage_errors, lit_errors,
    count_errors, closed, failed and per_light. Raises as render does."""
    ...
