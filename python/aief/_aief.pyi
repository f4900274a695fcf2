# Types of the compiled module aief._aief (python/*.cpp), for IDEs and mypy; python/aief/__init__.py
# re-exports it. python/tests/test_api_docs.py checks that every public name of the module is here.
import os
from typing import Any, Literal, Optional, Sequence, TypedDict, Union

import numpy
import numpy.typing

# A 2-D uint8 gray image, or H x W x 3 BGR / H x W x 4 BGRA uint8 (anything numpy.asarray takes).
ImageLike = numpy.typing.ArrayLike
# A file name: str (undecodable bytes as os.fsdecode keeps them), bytes or os.PathLike.
PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
# N x 2 points (x, y).
PointsLike = numpy.typing.ArrayLike
MatcherName = Literal["mutual", "ratio", "paper", "mutual_ratio", "guided"]

__version__: str

class Error(ValueError):
    """Bad input or options (a ValueError): the engine's message says what and where."""

class ExtractionInfo(TypedDict):
    entropy_threshold_requested: float
    entropy_threshold_used: float
    threshold_lowered: bool
    image_entropy_bits: float
    blocks_total: int
    blocks_kept: int
    auto_threshold_effectiveness: float

class SweepPoint(TypedDict):
    threshold: float
    kept_blocks: int
    kept_blocks_b: int
    keypoints_a: int
    keypoints_b: int
    putative: int
    inliers: int
    cmr: float
    eligible: bool

class Features:
    """Keypoints and descriptors of one image, as numpy arrays."""
    @property
    def keypoints(self) -> numpy.ndarray:
        """N x 2 float32, (x, y) in level-0 pixels, pixel centres at integers."""
    @property
    def size(self) -> numpy.ndarray:
        """N float32, patch diameter at the keypoint's level, level-0 pixels."""
    @property
    def angle(self) -> numpy.ndarray:
        """N float32, orientation in degrees, [0, 360)."""
    @property
    def response(self) -> numpy.ndarray:
        """N float32, FAST score."""
    @property
    def octave(self) -> numpy.ndarray:
        """N int32, pyramid level."""
    @property
    def descriptors(self) -> numpy.ndarray:
        """N x 32 uint8, 256 bits: rBRIEF or the box descriptor (see descriptor)."""
    @property
    def descriptor(self) -> Literal["rbrief", "box"]:
        """Which descriptor the rows hold; sets of different descriptors never match."""
    @property
    def info(self) -> ExtractionInfo:
        """How the entropy mask went (threshold used, blocks kept)."""
    @property
    def image_width(self) -> int: ...
    @property
    def image_height(self) -> int: ...
    def __len__(self) -> int: ...

class Extractor:
    """ORB features with the AIEF entropy mask; invalid options raise aief.Error."""
    # Parameters, their order and defaults: the option table's rows (core/options/extractor_option_rows.cpp);
    # python/tests/test_stub.py holds them to it. The keys of Extractor.options are keywords too.
    def __init__(
        self,
        n_features: int = 1000,
        mode: str = "aief",
        entropy_threshold: Union[float, Literal["auto", "carried"]] = 4.0,
        n_levels: Optional[int] = None,
        scale_factor: Optional[float] = None,
        threads: int = 0,
        kernels: str = "auto",
        *,
        fast_threshold: int = 20,
        fast_min_threshold: int = 7,
        block_size: int = 32,
        entropy: Optional[str] = None,
        carry_every: int = 30,
        coordinates: Optional[str] = None,
        subpixel: Optional[bool] = None,
        candidate_pool: Optional[Union[float, Literal["inf", "off"]]] = None,
        candidate_ranking: Optional[str] = None,
        starvation_guard: Optional[str] = None,
        auto_skips_uniform_blocks: Optional[bool] = None,
        auto_requires_two_classes: Optional[bool] = None,
        pyramid_resampling: Optional[Literal["q8", "opencv"]] = None,
        detection_cells: Optional[Literal["blocks", "orbslam"]] = None,
        quadtree_ties: Optional[Literal["full", "orbslam"]] = None,
        orientation: Optional[Literal["atan2", "fast-atan2"]] = None,
        quadtree_weight: Literal["none", "entropy"] = "none",
        fast_threshold_from: Literal["none", "entropy"] = "none",
        low_entropy_sharpen: bool = False,
        descriptor: Optional[Literal["rbrief", "box"]] = None,
        detection_smoothing: Optional[float] = None,
        scale_selection: Literal["off", "extrema"] = "off",
        max_image_pixels: int = 67108864,
        **record_keys: Any,  # and the earlier keywords, still accepted: threshold, levels, scale, ...
    ) -> None: ...
    def extract(self, image: ImageLike, mask: Optional[numpy.typing.ArrayLike] = None) -> Features:
        """Features of a gray, BGR or BGRA uint8 image; mask (2-D uint8 or bool, non-zero where
        keypoints may be) acts before the distribution, so the budget is filled inside it. The GIL
        is released meanwhile."""
    def describe(
        self,
        image: ImageLike,
        keypoints: Union[Features, numpy.typing.ArrayLike],
        octave: Optional[numpy.typing.ArrayLike] = None,
        size: Optional[numpy.typing.ArrayLike] = None,
        angle: Optional[numpy.typing.ArrayLike] = None,
        response: Optional[numpy.typing.ArrayLike] = None,
        keep_angles: bool = False,
    ) -> tuple[Features, numpy.ndarray]:
        """Descriptors of given keypoints (Features or N x 2 (x, y)), computed as for detected ones:
        (features of the kept keypoints, their int32 indices). Angles recomputed unless keep_angles;
        keypoints closer than 19 pixels to their level's edge are removed."""
    # Defined in python/aief/__init__.py (need cv2): as cv2.Feature2D's methods.
    def detectAndCompute(self, image: ImageLike, mask: Optional[numpy.typing.ArrayLike] = None) -> tuple[list[Any], numpy.ndarray]: ...
    def detect(self, image: ImageLike, mask: Optional[numpy.typing.ArrayLike] = None) -> list[Any]: ...
    def compute(self, image: ImageLike, keypoints: list[Any], recompute_angles: bool = False) -> tuple[list[Any], numpy.ndarray]: ...
    @property
    def options(self) -> dict[str, Any]:
        """Every option in effect, as a dict."""
    @property
    def option_record(self) -> str:
        """The options as aief's output files record them: every field, one line of JSON."""
    @property
    def kernel_name(self) -> str:
        """The SIMD kernel set this extractor runs."""

class AdaptResult:
    """The sweep of the entropy threshold F over a pair."""
    @property
    def found(self) -> bool: ...
    @property
    def threshold(self) -> float: ...
    @property
    def chosen_index(self) -> int: ...
    @property
    def image_entropy_bits(self) -> float: ...
    @property
    def curve(self) -> list[SweepPoint]: ...
    @property
    def features_a(self) -> Features: ...
    @property
    def features_b(self) -> Features: ...
    @property
    def matches(self) -> numpy.ndarray: ...
    @property
    def homography(self) -> tuple[Optional[numpy.ndarray], numpy.ndarray]: ...

# The options of match, find_homography and adapt: the rows of core/options/matching_option_rows.cpp
# (python/tests/test_stub.py holds them to it).
def match(
    a: Union[numpy.typing.ArrayLike, Features],
    b: Union[numpy.typing.ArrayLike, Features],
    matcher: MatcherName = "mutual",
    ratio: Optional[float] = None,
    max_distance: int = 256,
    epipolar_band: Optional[float] = None,
) -> numpy.ndarray:
    """Hamming matches of a into b: M x 3 int32 (query, train, distance), sorted by query."""

def find_homography(
    src: PointsLike,
    dst: PointsLike,
    threshold_px: float = 3.0,
    confidence: float = 0.995,
    max_iterations: int = 10000,
    seed: int = 24301,
) -> tuple[Optional[numpy.ndarray], numpy.ndarray]:
    """RANSAC homography src -> dst: (H 3 x 3 float64 or None, N uint8 inlier mask)."""

def adapt(
    image_a: ImageLike,
    image_b: ImageLike,
    extractor: Optional[Extractor] = None,
    first_threshold: float = 0.0,
    step: float = 0.2,
    min_inliers: int = 20,
    matcher: MatcherName = "mutual",
    ratio: Optional[float] = None,
    max_distance: int = 256,
    epipolar_band: Optional[float] = None,
) -> AdaptResult:
    """The paper's sweep of F over a pair: the chosen threshold, the curve, features and matches at it."""

def read_image(path: PathLike) -> numpy.ndarray:
    """An image file as the aief CLI reads it: 2-D uint8 gray."""

class FeaturesFile:
    """An hloc features file (HDF5) written by the engine's writer, as aief extract --batch --format h5
    writes it; a failed write (a full disk) raises aief.Error and keeps every group complete before it."""
    def __init__(self, path: PathLike) -> None: ...
    def is_current(self, name: str, source: tuple[int, int], extractor: Extractor) -> bool:
        """Whether `name` is a complete group of the image file `source` ((size, mtime in ns)) with `extractor`'s options."""
    def write(self, name: str, features: Features, source: tuple[int, int], extractor: Extractor) -> None:
        """Writes the group `name` with the features, the source record and the option record."""
    def remove(self, name: str) -> None:
        """Removes the group `name`, if there is one."""
    @property
    def writes_on_disk(self) -> int:
        """How many of this object's writes the file on disk holds (after a failed write: those before it that reached the disk)."""
    def close(self) -> None:
        """Closes the file, raising aief.Error when its last writes could not be stored."""
    def __enter__(self) -> FeaturesFile: ...
    def __exit__(self, *exc: Any) -> None: ...

def batch_inputs(folder_or_list: PathLike) -> list[tuple[str, str]]:
    """The images `aief extract --batch FOLDER_OR_LIST` takes, as (path, name) pairs sorted by name."""

def option_changes(record: Optional[str], extractor: Extractor) -> list[str]:
    """What an output recorded with `record` (None: no record) does not share with `extractor`'s
    options ("n_features 500 -> 3000"); empty when the extractor would write the same output."""

def default_options() -> dict[str, Any]:
    """The C++ ExtractorOptions defaults, as a dict."""
