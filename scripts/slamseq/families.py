"""The sequence families: what changes between them, one table.

All families of one seed share the room's geometry and (except `fast_rotation`) the camera path,
so each differs from `baseline` in one thing only: the lighting, the textures, the exposure time
or the noise. `weak_texture` uses the same room with low-contrast textures; `blank_walls` the
same room with flat walls, floor and ceiling (a few posters on the walls, the boxes textured)
seen through shot and read noise, the scene an entropy mask was made for.
"""
from dataclasses import dataclass
from typing import Callable

import numpy as np

from slamseq.render import Light


@dataclass(frozen=True)
class Family:
    name: str
    what: str                       # one line for docs and sequence.json
    fast_rotation: bool = False     # the path (slamseq.paths)
    weak_texture: bool = False      # the room's textures (slamseq.scene.make_room contrast)
    moving_light: bool = False
    exposure: float = 0.004         # seconds the shutter is open (motion blur)
    gain: Callable = None           # t -> exposure gain (1 = baseline)
    gamma: Callable = None          # t -> gamma applied by the camera (1 = linear)
    low_light: bool = False         # dim scene, shot and read noise, then digital gain
    read_noise: float = 1.0         # grey levels, before quantisation
    blank_walls: bool = False       # the room's own faces flat (slamseq.scene.make_room)
    shot_noise: float = 0.0         # photon noise variance per grey level of signal (0: none)


def _auto_exposure_gain(t):
    """A slow swell plus the jumps of an auto-exposure that corrects in steps every 2.5 s."""
    step = 1.3 ** ((-1) ** int(t / 2.5))
    return (1.0 + 0.35 * np.sin(2 * np.pi * t / 6.0)) * step


FAMILIES = [
    Family("baseline", "ceiling lights, textured room, translating path"),
    Family("fast_rotation", "the baseline path plus 0.6 Hz yaw / 0.8 Hz pitch oscillations (peaks ~110 deg/s)", fast_rotation=True),
    Family("light_change", "exposure gain swell and steps (x0.5-1.8), gamma 0.65-1.35, a light circling the room",
           moving_light=True, gain=_auto_exposure_gain, gamma=lambda t: 1.0 + 0.35 * np.sin(2 * np.pi * t / 8.5 + 1.0)),
    Family("weak_texture", "the same room with textures at 20% contrast and few shapes", weak_texture=True),
    Family("motion_blur", "shutter open 45 ms of the 50 ms frame", exposure=0.045),
    Family("low_light", "scene at 15% exposure with shot and read noise, then x2.5 digital gain", low_light=True),
    Family("blank_walls", "flat walls, floor and ceiling with a few posters, textured boxes; shot and read noise",
           blank_walls=True, read_noise=2.0, shot_noise=0.15),
]

BY_NAME = {family.name: family for family in FAMILIES}


def lights(family, room_size, t):
    """Point lights and ambient level at time t."""
    w, d, h = room_size
    ceiling = [Light((w / 3, d / 2, h - 0.1), 0.8), Light((2 * w / 3, d / 2, h - 0.1), 0.8)]
    if not family.moving_light:
        return ceiling, 0.35
    angle = 2 * np.pi * t / 10.0
    moving = Light((w / 2 + 2.5 * np.cos(angle), d / 2 + 2.0 * np.sin(angle), 1.0 + 0.6 * np.sin(3 * angle)), 2.2, 3.0)
    return [Light(ceiling[0].position, 0.35), moving], 0.12


def sensor(family, radiance, t, rng):
    """Grey levels (uint8) a camera records from radiance (albedo x light, about 0..1.2)."""
    signal = 0.85 * radiance * (family.gain(t) if family.gain else 1.0)
    if family.gamma:
        signal = np.power(np.clip(signal, 0.0, None), 1.0 / family.gamma(t))
    levels = 255.0 * signal
    if family.low_light:
        dim = 0.15 * levels
        dim = dim + rng.normal(0.0, 1.0, dim.shape) * np.sqrt(0.6 * np.clip(dim, 0, None) + 1.2 ** 2)
        levels = 2.5 * dim
    elif family.shot_noise > 0:
        variance = family.shot_noise * np.clip(levels, 0, None) + family.read_noise ** 2
        levels = levels + rng.normal(0.0, 1.0, levels.shape) * np.sqrt(variance)
    else:
        levels = levels + rng.normal(0.0, family.read_noise, levels.shape)
    return np.clip(np.rint(levels), 0, 255).astype(np.uint8)
