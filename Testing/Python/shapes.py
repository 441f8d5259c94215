"""Analytic shapes shared by the pvpython tests."""
import math

import numpy as np


def sphere(n, radius=1.0):
    """(points, unit outward normals) of a Fibonacci sphere of n points: every point exactly on the sphere."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = np.sqrt(1 - z * z)
    a = math.pi * (3 - math.sqrt(5)) * np.arange(n)
    normals = np.stack([r * np.cos(a), r * np.sin(a), z], axis=1)
    return radius * normals, normals
