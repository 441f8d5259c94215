"""Growing Least Squares VTK filters (module GLS::Filters) for Python, on ParaView's VTK.

    from glsvtk import vtkGLSScaleSpace
"""
from .vtkGLSFilters import *  # noqa: F401,F403
