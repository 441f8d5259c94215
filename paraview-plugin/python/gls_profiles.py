"""The main job's scale profiles: a few telling points of the analysed cloud, and kappa and nu against finely
sampled scales for them (from a GLS Scale Profiles table), plotted with their pertinent scales."""
import numpy as np

import gls_cloud


def select_profile_points(feature, pertinent_count):
    """A few telling points, each once: the flattest, the most featured, a median one, one with several pertinent
    scales. `feature` must have a finite value."""
    valid = np.where(np.isfinite(feature))[0]
    values = feature[valid]
    # The points at ranks 0, n // 2 and n - 1 of the stable order by feature (ties in index order), without sorting:
    # the k-th value by partition, then the right one among the points of that value.
    def at_rank(k):
        value = np.partition(values, k)[k]
        ties = valid[values == value]
        return ties[k - np.count_nonzero(values < value)]
    candidates = [('lowest feature', at_rank(0)), ('median feature', at_rank(len(valid) // 2)),
                  ('highest feature', at_rank(len(valid) - 1))]
    several = np.where(pertinent_count >= 2)[0]
    if len(several):
        candidates.append(('2+ pertinent scales', several[len(several) // 2]))
    picks = {}
    for label, pid in candidates:
        if int(pid) not in picks.values():
            picks[label] = int(pid)
    return picks


# The points the crop (around) tests against the profiles' points at a time: bounds its scratch (a few bytes a point).
CROP_CHUNK = 1 << 22


def around(polydata, ids, reach):
    """The points of `polydata` within `reach` of the points `ids` along every axis (a box, which holds the ball of
    radius reach), with their Normals, as a vertex cloud, and the ids' indices in it: all that the fits of those
    points at scales up to `reach` read, so that their profiles need not gather the whole cloud (which, at 10^7
    points, took 1.1 GiB above what the job held)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    points = vtk_to_numpy(polydata.GetPoints().GetData())
    centres = points[list(ids)].astype(float)
    keep = np.zeros(len(points), dtype=bool)
    for start in range(0, len(points), CROP_CHUNK):
        block = points[start:start + CROP_CHUNK]
        inside = np.zeros(len(block), dtype=bool)
        for centre in centres:
            inside |= np.all(np.abs(block - centre) <= reach, axis=1)
        keep[start:start + CROP_CHUNK] = inside
    index = np.flatnonzero(keep)
    normals = vtk_to_numpy(polydata.GetPointData().GetArray('Normals'))
    return (gls_cloud.vertex_cloud(points[index], {'Normals': normals[index]}),
            [int(i) for i in np.searchsorted(index, list(ids))])


# nu differences below this are rounding noise (gls::kVariationNoise: nu is about 1e-20 on a sphere).
VARIATION_NOISE = 1e-12


def profile_minima(nu, count=3):
    """The indices of the `count` lowest strict local minima of a profile's nu (gls::isPertinentScale's rule),
    in increasing order: the pertinent scales of the finely sampled profile."""
    inner = np.arange(1, len(nu) - 1)
    minima = inner[(nu[inner] < nu[inner - 1] - VARIATION_NOISE) & (nu[inner] <= nu[inner + 1] + VARIATION_NOISE)]
    return np.sort(minima[np.argsort(nu[minima], kind='stable')][:count])


def plot_profiles(path, title, table, picks, columns=None):
    """kappa and nu against scale for the picked points ({label: point id}), from a GLS Scale Profiles table (finely
    sampled), with the pertinent scales of each profile dotted. `columns`: {label: the id the table's columns name},
    when the table was computed on another cloud than the one the ids number (around)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def column(name):
        return vtk_to_numpy(table.GetColumnByName(name))

    t = column('t')
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for label, pid in picks.items():
        cid = pid if columns is None else columns[label]
        line, = ax1.plot(t, column('t*kappa (%d)' % cid) / t, label='%s (point %d)' % (label, pid))
        nu = column('nu (%d)' % cid)
        ax2.semilogy(t, np.maximum(nu, 1e-12), color=line.get_color())
        for k in profile_minima(nu):
            ax2.axvline(t[k], color=line.get_color(), ls=':', lw=1)
    ax1.set_ylabel('kappa (1/length)')
    ax1.axhline(0, color='gray', lw=0.5)
    ax1.legend(fontsize=8)
    ax1.set_title(title)
    ax2.set_ylabel('nu (dimensionless, log)')
    ax2.set_xlabel('scale t (length), %d scales; dotted: pertinent scales' % len(t))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
