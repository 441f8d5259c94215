"""The main job's scale profiles: a few telling points of the analysed cloud, and kappa and nu against finely
sampled scales for them (from a GLS Scale Profiles table), plotted with their pertinent scales."""
import numpy as np


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


# nu differences below this are rounding noise (gls::kVariationNoise: nu is about 1e-20 on a sphere).
VARIATION_NOISE = 1e-12


def profile_minima(nu, count=3):
    """The indices of the `count` lowest strict local minima of a profile's nu (gls::isPertinentScale's rule),
    in increasing order: the pertinent scales of the finely sampled profile."""
    inner = np.arange(1, len(nu) - 1)
    minima = inner[(nu[inner] < nu[inner - 1] - VARIATION_NOISE) & (nu[inner] <= nu[inner + 1] + VARIATION_NOISE)]
    return np.sort(minima[np.argsort(nu[minima], kind='stable')][:count])


def plot_profiles(path, title, table, picks):
    """kappa and nu against scale for the picked points, from a GLS Scale Profiles table (finely sampled), with
    the pertinent scales of each profile dotted."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def column(name):
        return vtk_to_numpy(table.GetColumnByName(name))

    t = column('t')
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for label, pid in picks.items():
        line, = ax1.plot(t, column('t*kappa (%d)' % pid) / t, label='%s (point %d)' % (label, pid))
        nu = column('nu (%d)' % pid)
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
