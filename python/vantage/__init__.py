"""Vantage: next-best-view planning in cluttered 3D scenes (Potthast & Sukhatme).

Python bindings of the C++ library. Poses are 4 x 4 rigid transforms T_world_sensor (sensor
frame: x forward, y left, z up), point clouds N x 3 arrays [m], grid arrays indexed [i, j, k].
Errors raise ValueError for bad arguments and malformed files, OSError for files that cannot be
read or written, MemoryError for a grid larger than the memory available (checked before it is
allocated) and RuntimeError otherwise, with the library's one-line messages.
"""

from ._vantage import *  # noqa: F401,F403
