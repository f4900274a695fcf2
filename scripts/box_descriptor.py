"""The box descriptor in numpy: tables, tests on keypoints, synthetic pairs, boosting, MMA.

A table is 256 box-average tests, one a line "x1 y1 x2 y2 radius threshold" (the format of
data/box_descriptor/README.md and core/kernels/box_describe.hpp): box centres in patch pixels of
a 32 x 32 patch, origin at its centre, both boxes squares of side 2 radius + 1, and
bit = 1 iff mean(box 1) - mean(box 2) <= threshold. A keypoint of size S (31 at its own level) and
angle A maps a patch point p to centre + (S / 32) R(A) p, rounded half to even, and a radius r to
rint(r S / 32); boxes are clipped to the image as OpenCV's BEBLID clips them.

Where the boxes are read (`integral`): "level" (the engine's choice) reads the integral image of
the keypoint's own pyramid level, made here with cv2.resize INTER_LINEAR level by level (the
engine's Q8 pyramid has the same geometry, its rounding differs by at most a gray level), at
scale 31 / 32; "level0" reads level 0 at scale size / 32.

Used by scripts/train_box_descriptor.py (training and evaluation) and scripts/tests.
"""
import math

import cv2
import numpy as np

PATCH_SIDE = 32
PATCH_SIZE_AT_LEVEL = 31.0  # kPatchSize: a keypoint's size at its own level


# ----------------------------------------------------------------------------- tables

class Table:
    """Tests as arrays: geometry (n x 5 ints: x1 y1 x2 y2 radius) and thresholds (n floats)."""

    def __init__(self, geometry, thresholds, header=""):
        self.geometry = np.asarray(geometry, dtype=np.int32).reshape(-1, 5)
        self.thresholds = np.asarray(thresholds, dtype=np.float64).reshape(-1)
        self.header = header
        if len(self.geometry) != len(self.thresholds):
            raise ValueError("geometry and thresholds differ in length")

    def __len__(self):
        return len(self.thresholds)


def read_table(path):
    geometry, thresholds, header = [], [], []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                header.append(text[1:].strip())
                continue
            fields = text.split()
            if len(fields) != 6:
                raise ValueError(f"{path}:{number}: expected 'x1 y1 x2 y2 radius threshold'")
            geometry.append([int(v) for v in fields[:5]])
            thresholds.append(float(fields[5]))
    return Table(geometry, thresholds, "\n".join(header))


def format_threshold(value):
    """At most two decimals (the engine compiles thresholds in hundredths), no '-0'."""
    text = f"{round(float(value), 2):.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def write_table(path, table, header_lines):
    with open(path, "w", encoding="utf-8") as f:
        for line in header_lines:
            f.write(("# " + line).rstrip() + "\n")
        for (x1, y1, x2, y2, r), t in zip(table.geometry.tolist(), table.thresholds.tolist()):
            f.write(f"{x1} {y1} {x2} {y2} {r} {format_threshold(t)}\n")


def check_table(table):
    """The ranges the engine's table generator accepts (cmake/generate_box_table.cmake)."""
    g = table.geometry
    if len(table) != 256:
        raise ValueError(f"{len(table)} tests, expected 256")
    if g[:, :4].min() < -16 or g[:, :4].max() > 16 or g[:, 4].min() < 0 or g[:, 4].max() > 16:
        raise ValueError("coordinates outside [-16, 16] or radius outside [0, 16]")
    if np.abs(table.thresholds).max() > 255:
        raise ValueError("threshold outside [-255, 255]")


def candidate_pool(count, rng, max_radius=7):
    """Random box pairs, both boxes inside the patch ([-16, 15] per axis, as TEBLID's) and apart."""
    out = np.empty((count, 5), dtype=np.int32)
    filled = 0
    seen = set()
    while filled < count:
        r = int(rng.integers(1, max_radius + 1))
        lo, hi = -16 + r, 15 - r
        x1, y1, x2, y2 = (int(v) for v in rng.integers(lo, hi + 1, size=4))
        if (x1, y1) == (x2, y2) or (x1, y1, x2, y2, r) in seen or (x2, y2, x1, y1, r) in seen:
            continue
        seen.add((x1, y1, x2, y2, r))
        out[filled] = (x1, y1, x2, y2, r)
        filled += 1
    return out


# ----------------------------------------------------------------------------- keypoints, pyramid

class Keypoints:
    """x, y in level-0 pixels (pixel centres at integers), size, angle (degrees), octave."""

    def __init__(self, xy, size, angle, octave, rbrief=None):
        self.xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        self.size = np.asarray(size, dtype=np.float64).reshape(-1)
        self.angle = np.asarray(angle, dtype=np.float64).reshape(-1)
        self.octave = np.asarray(octave, dtype=np.int64).reshape(-1)
        self.rbrief = rbrief

    def __len__(self):
        return len(self.size)

    def subset(self, index):
        return Keypoints(self.xy[index], self.size[index], self.angle[index], self.octave[index],
                         None if self.rbrief is None else self.rbrief[index])


def extract(extractor, gray):
    f = extractor.extract(gray)
    return Keypoints(f.keypoints, f.size, f.angle, f.octave, np.asarray(f.descriptors))


class Pyramid:
    """Integral images of level 0 and of the levels a scale factor makes (made when first asked)."""

    def __init__(self, gray, scale_factor=1.2):
        self.levels = [np.ascontiguousarray(gray, dtype=np.uint8)]
        self.scale_factor = scale_factor
        self.integrals = {}

    def level(self, n):
        while len(self.levels) <= n:
            h0, w0 = self.levels[0].shape
            scale = np.float32(1.0)
            for _ in range(len(self.levels)):
                scale = np.float32(scale * np.float32(self.scale_factor))
            size = (int(np.rint(np.float32(w0) / scale)), int(np.rint(np.float32(h0) / scale)))
            self.levels.append(cv2.resize(self.levels[-1], size, interpolation=cv2.INTER_LINEAR))
        return self.levels[n]

    def integral(self, n):
        if n not in self.integrals:
            self.integrals[n] = cv2.integral(self.level(n), sdepth=cv2.CV_64F).astype(np.int64)
        return self.integrals[n]


def placements(pyramid, kps, integral_mode):
    """Per keypoint: the level read, its centre in that level's pixels, the patch-to-image scale."""
    if integral_mode == "level0":
        return (np.zeros(len(kps), dtype=np.int64), kps.xy.copy(),
                kps.size / PATCH_SIDE)
    if integral_mode != "level":
        raise ValueError(integral_mode)
    h0, w0 = pyramid.levels[0].shape
    centres = np.empty_like(kps.xy)
    for n in np.unique(kps.octave):
        sel = kps.octave == n
        h, w = pyramid.level(int(n)).shape
        centres[sel, 0] = (kps.xy[sel, 0] + 0.5) * (w / w0) - 0.5
        centres[sel, 1] = (kps.xy[sel, 1] + 0.5) * (h / h0) - 0.5
    # The engine describes the detected level pixel: the sub-pixel offset (within +-0.5) is only
    # in the output position.
    centres = np.rint(centres)
    return kps.octave.copy(), centres, np.full(len(kps), PATCH_SIZE_AT_LEVEL / PATCH_SIDE)


# ----------------------------------------------------------------------------- box tests

def _box_sums(integral, cx, cy, radius):
    """Sums and areas of boxes [c - R, c + R] clipped as BEBLID clips them (never empty)."""
    h, w = integral.shape[0] - 1, integral.shape[1] - 1
    x0 = np.clip(cx - radius, 0, w - 1)
    x1 = np.clip(cx + radius + 1, 1, w)
    y0 = np.clip(cy - radius, 0, h - 1)
    y1 = np.clip(cy + radius + 1, 1, h)
    s = integral[y1, x1] - integral[y0, x1] - integral[y1, x0] + integral[y0, x0]
    return s, (x1 - x0) * (y1 - y0)


def _rotation(angle_deg, scale):
    """a = s cos, b = s sin in float32, as the engine computes them."""
    t = np.float32(angle_deg) * np.float32(math.pi / 180.0)
    a = np.float32(scale) * np.cos(t).astype(np.float32)
    b = np.float32(scale) * np.sin(t).astype(np.float32)
    return a, b


def _by_level(pyramid, kps, integral_mode):
    """Per level read: the rows of its keypoints, and box_sums(g) of tests g (float32, n x 5) at
    them: [(sums, areas) of box 1, (sums, areas) of box 2], each len(rows) x n, as the engine
    places the boxes (rotated and scaled about the keypoint, rounded to pixels)."""
    levels, centres, scales = placements(pyramid, kps, integral_mode)
    for n in np.unique(levels):
        rows = np.flatnonzero(levels == n)
        integral = pyramid.integral(int(n))
        a, b = _rotation(kps.angle[rows].astype(np.float32), scales[rows].astype(np.float32))
        x = centres[rows, 0].astype(np.float32)[:, None]
        y = centres[rows, 1].astype(np.float32)[:, None]
        a, b = a[:, None], b[:, None]
        scale = scales[rows, None].astype(np.float32)

        def box_sums(g):
            radius = np.rint(scale * g[:, 4]).astype(np.int64)
            sums = []
            for px, py in ((g[:, 0], g[:, 1]), (g[:, 2], g[:, 3])):
                cx = np.rint(x + (px * a - py * b)).astype(np.int64)
                cy = np.rint(y + (px * b + py * a)).astype(np.int64)
                sums.append(_box_sums(integral, cx, cy, radius))
            return sums

        yield rows, box_sums


def responses(pyramid, kps, geometry, integral_mode="level", chunk=512):
    """mean(box 1) - mean(box 2) per keypoint and test: float32, len(kps) x len(geometry)."""
    geometry = np.asarray(geometry, dtype=np.int64).reshape(-1, 5)
    out = np.empty((len(kps), len(geometry)), dtype=np.float32)
    for rows, box_sums in _by_level(pyramid, kps, integral_mode):
        for start in range(0, len(geometry), chunk):
            (s1, a1), (s2, a2) = box_sums(geometry[start:start + chunk].astype(np.float32))
            out[rows, start:start + chunk] = s1 / a1 - s2 / a2
    return out


def describe(pyramid, kps, table, integral_mode="level"):
    """Bits (len(kps) x len(table), uint8 0/1), the engine's test exactly in integers."""
    geometry = table.geometry.astype(np.float32)
    hundredths = np.rint(table.thresholds * 100).astype(np.int64)
    bits = np.empty((len(kps), len(table)), dtype=np.uint8)
    for rows, box_sums in _by_level(pyramid, kps, integral_mode):
        (s1, a1), (s2, a2) = box_sums(geometry)
        bits[rows] = (100 * s1 * a2 - 100 * s2 * a1 <= hundredths * a1 * a2)
    return bits


# Synthetic pairs (scripts/box_pair_geometry.py), re-exported for the callers of this module.
from box_pair_geometry import (  # noqa: E402,F401
    homography, perspective_tilt, photometric, warp, random_training_pair, project, local_scale)


def hamming_rbrief(a, b):
    """Hamming distances between packed descriptors (n x 32 and m x 32 uint8)."""
    return hamming_bits(np.unpackbits(a, axis=1), np.unpackbits(b, axis=1))


def hamming_bits(a, b):
    a = a.astype(np.float32)
    b = b.astype(np.float32)
    return (a @ (1.0 - b).T + (1.0 - a) @ b.T).astype(np.int32)


def training_pairs(kps1, kps2, h, rng, max_positives=200, positive_px=1.5, negative_px=10.0,
                   max_level_ratio=1.3):
    """Index pairs (i in kps1, j in kps2) and labels (1 corresponding, 0 not).

    Positives: kps1[i] projected by h lies within positive_px of kps2[j], the two are each other's
    nearest, and their sizes agree with the warp's local scale within max_level_ratio. For each
    positive, two negatives: the keypoint of kps2 at least negative_px from the projection whose
    rBRIEF is nearest (the confusion a matcher would make), and a random one."""
    if len(kps1) == 0 or len(kps2) == 0:
        return np.zeros((0, 2), dtype=np.int64), np.zeros(0, dtype=np.int8)
    p = project(h, kps1.xy)
    d = np.linalg.norm(p[:, None, :] - kps2.xy[None, :, :], axis=2)
    nearest = d.argmin(axis=1)
    back = d.argmin(axis=0)
    i = np.flatnonzero((d[np.arange(len(p)), nearest] <= positive_px) &
                       (back[nearest] == np.arange(len(p))))
    j = nearest[i]
    expected = kps1.size[i] * local_scale(h, kps1.xy[i])
    ratio = np.abs(np.log(kps2.size[j] / expected))
    keep = ratio <= math.log(max_level_ratio)
    i, j = i[keep], j[keep]
    if len(i) > max_positives:
        pick = rng.choice(len(i), max_positives, replace=False)
        i, j = i[pick], j[pick]
    far = d[i] > negative_px
    some = far.any(axis=1)  # a positive needs a keypoint far enough to be its negative
    i, j, far = i[some], j[some], far[some]
    hard = hamming_rbrief(kps1.rbrief[i], kps2.rbrief)
    hard = np.where(far, hard, 1 << 20).argmin(axis=1)
    rand = np.array([rng.choice(np.flatnonzero(row)) for row in far], dtype=np.int64)
    pairs = np.concatenate([np.stack([i, j], 1), np.stack([i, hard], 1), np.stack([i, rand], 1)])
    labels = np.concatenate([np.ones(len(i)), np.zeros(2 * len(i))]).astype(np.int8)
    return pairs.astype(np.int64), labels


# ----------------------------------------------------------------------------- boosting

def threshold_grid(max_abs=80.0):
    """The thresholds a test may take (mean gray-level differences): every integer up to 12, then
    coarser, up to max_abs. Large thresholds read contrast, which lighting changes."""
    inner = np.arange(-12.0, 12.01, 1.0)
    outer = np.array([15, 18, 22, 27, 33, 40, 50, 62, 80], dtype=np.float64)
    outer = outer[outer <= max_abs]
    grid = np.concatenate([-outer[::-1], inner, outer])
    return grid[np.abs(grid) <= max_abs]


def bins(values, grid):
    """bin(r) = the number of thresholds below r, so r <= grid[k] iff bin(r) <= k."""
    return np.searchsorted(grid, values, side="left").astype(np.uint8)


def boost(bins1, bins2, labels, grid, n_bits=256, shrinkage=0.1, refresh=1, shortlist=256,
          max_correlation=1.0, triplets=None, rate=0.05, chunk=128, progress=None):
    """BEBLID's boosting with equal-weight bits: each round picks the (test, threshold) whose bits
    agree on the most weight of positive pairs and differ on the most weight of negative pairs,
    then reweights the pairs (AdaBoost, exponential loss), so the next bit is chosen for the
    pairs the chosen ones get wrong: bits that say the same thing are not chosen twice. The
    reweighting is damped (alpha x shrinkage): undamped, a few dozen bits put all the weight on
    pairs no single test separates (hard negatives, mislabelled positives) and the later bits
    are chosen on noise; damped, every bit still separates the whole set well.

    With refresh > 1, every candidate is scored only every `refresh` rounds; the rounds between
    score the `shortlist` best of the last full scoring (damped weights move slowly, so the best
    candidate is almost always among them). refresh = 1 is exact.

    max_correlation < 1: a test whose bit correlates more than that (absolute Pearson, over the
    keypoints of the pairs) with a bit already chosen is passed over for the best one that does
    not, among the 64 best of the round (the least correlated of them if none qualifies):
    correlated bits count the same evidence twice in a Hamming distance.

    triplets (T x 2: the index of a positive pair and of a negative pair with the same anchor):
    the pairs are weighted by triplet instead, as TEBLID learns, each triplet by
    exp(-rate x its margin so far: the bits its negative pair differs in less those its positive
    pair differs in), so each bit is chosen for the triplets whose positive is not yet nearer
    than their negative, which is what nearest-neighbour matching needs.

    bins1, bins2: candidates x pairs (uint8, `bins` of the two keypoints' responses); labels 1/0.
    Returns [(candidate, threshold index, weighted agreement)] in bit order."""
    n_candidates, n_pairs = bins1.shape
    n_thresholds = len(grid)
    width = n_thresholds + 1
    lo = np.minimum(bins1, bins2)
    hi = np.maximum(bins1, bins2)
    sign = np.where(labels > 0, 1.0, -1.0)
    weights = np.where(labels > 0, 0.5 / max(1, (labels > 0).sum()),
                       0.5 / max(1, (labels <= 0).sum()))
    used = np.zeros(n_candidates, dtype=bool)
    last = np.full(n_candidates, -np.inf)

    def score(candidates, v):
        """Best weighted agreement and its threshold index for each of the candidates."""
        best_score = np.empty(len(candidates))
        best_k = np.empty(len(candidates), dtype=np.int64)
        total = v.sum()
        for start in range(0, len(candidates), chunk):
            rows = candidates[start:start + chunk]
            offsets = (np.arange(len(rows)) * width)[:, None]
            vv = np.broadcast_to(v, (len(rows), n_pairs)).ravel()
            hist = np.bincount((lo[rows] + offsets).ravel(), vv, len(rows) * width)
            hist -= np.bincount((hi[rows] + offsets).ravel(), vv, len(rows) * width)
            # differ[k] = sum of v over the pairs whose bits differ at threshold k: lo <= k < hi
            differ = np.cumsum(hist.reshape(len(rows), width), axis=1)[:, :n_thresholds]
            agreement = total - 2.0 * differ
            best_k[start:start + len(rows)] = agreement.argmax(axis=1)
            best_score[start:start + len(rows)] = agreement.max(axis=1)
        return best_score, best_k

    chosen = []
    # Keypoints for the correlations: the first keypoint of each pair (anchors repeat; at most 8000).
    sample = np.arange(n_pairs)
    if n_pairs > 8000:
        sample = np.random.default_rng(0).choice(n_pairs, 8000, replace=False)
    chosen_bits = np.zeros((0, len(sample)), dtype=np.float32)

    def standardised(rows, ks):
        b = (bins1[np.asarray(rows)[:, None], sample[None, :]] <= np.asarray(ks)[:, None])
        b = b.astype(np.float32)
        b -= b.mean(axis=1, keepdims=True)
        norm = np.linalg.norm(b, axis=1, keepdims=True)
        return b / np.maximum(norm, 1e-6)

    if triplets is not None:
        triplets = np.asarray(triplets, dtype=np.int64)
        margins = np.zeros(len(triplets))

    for round_ in range(n_bits):
        if triplets is None:
            v = weights * sign
        else:
            w = np.exp(-rate * (margins - margins.min()))
            w /= w.sum()
            v = (np.bincount(triplets[:, 0], w, n_pairs) - np.bincount(triplets[:, 1], w, n_pairs))
        if round_ % refresh == 0:
            candidates = np.flatnonzero(~used)
        else:
            order = np.argsort(-np.where(used, -np.inf, last), kind="stable")
            candidates = np.sort(order[:min(shortlist, int((~used).sum()))])
        scores, ks = score(candidates, v)
        last[candidates] = scores
        pick = int(np.argmax(scores))
        if max_correlation < 1.0 and len(chosen_bits):
            top = np.argsort(-scores, kind="stable")[:64]
            bits = standardised(candidates[top], ks[top])
            worst = np.abs(bits @ chosen_bits.T).max(axis=1)
            ok = np.flatnonzero(worst <= max_correlation)
            pick = int(top[ok[0]] if len(ok) else top[np.argmin(worst)])
        c, k, r = int(candidates[pick]), int(ks[pick]), float(scores[pick])
        if max_correlation < 1.0:
            chosen_bits = np.vstack([chosen_bits, standardised([c], [k])])
        used[c] = True
        differ = (bins1[c] <= k) != (bins2[c] <= k)
        if triplets is None:
            agree = np.where(differ, -1.0, 1.0)
            r = min(max(r / weights.sum(), -0.999999), 0.999999)
            alpha = shrinkage * 0.5 * math.log((1 + r) / (1 - r))
            weights = weights * np.exp(-alpha * sign * agree)
            weights /= weights.sum()
        else:
            r = r / np.abs(v).sum()
            margins += differ[triplets[:, 1]].astype(np.float64) - differ[triplets[:, 0]]
        chosen.append((c, k, r))
        if progress is not None:
            progress(round_, c, k, r)
    return chosen


# ----------------------------------------------------------------------------- evaluation

def mutual_nearest(bits1, bits2):
    if len(bits1) == 0 or len(bits2) == 0:
        return np.zeros((0, 2), dtype=np.int64)
    d = hamming_bits(bits1, bits2)
    fwd = d.argmin(axis=1)
    bwd = d.argmin(axis=0)
    i = np.flatnonzero(bwd[fwd] == np.arange(len(bits1)))
    return np.stack([i, fwd[i]], 1)


def match_accuracy(matches, kps1, kps2, h, px=3.0):
    """(correct, matched): matches whose kps1 point projected by h lies within px of kps2's."""
    if len(matches) == 0:
        return 0, 0
    err = np.linalg.norm(project(h, kps1.xy[matches[:, 0]]) - kps2.xy[matches[:, 1]], axis=1)
    return int((err <= px).sum()), len(matches)
