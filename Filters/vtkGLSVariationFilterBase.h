/**
 * @class   vtkGLSVariationFilterBase
 * @brief   The GLS scale filters that use the geometric variation nu: its weights, and nu of every point.
 *
 * nu(p, t) = WTau dtau^2 + WEta t^2 |deta|^2 + WKappa t^4 dkappa^2 (Mellado et al. 2012, eq. 5): dimensionless and
 * invariant to rigid motion and uniform scaling; low nu means the shape around p is stable at scale t; NaN where
 * the fit is undefined. See vtkGLSScaleFilterBase for the scales and where the samples come from.
 */
#ifndef vtkGLSVariationFilterBase_h
#define vtkGLSVariationFilterBase_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h"

#include <functional>

namespace gls
{
struct VariationWeights;
}

class VTKGLSFILTERS_EXPORT vtkGLSVariationFilterBase : public vtkGLSScaleFilterBase
{
public:
  vtkTypeMacro(vtkGLSVariationFilterBase, vtkGLSScaleFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Weights of the three terms of nu (dimensionless, default 1). Each must be finite and >= 0, and one positive;
  /// otherwise RequestData stops with an error naming the weight.
  vtkSetMacro(WTau, double);
  vtkGetMacro(WTau, double);
  vtkSetMacro(WEta, double);
  vtkGetMacro(WEta, double);
  vtkSetMacro(WKappa, double);
  vtkGetMacro(WKappa, double);
  ///@}

protected:
  vtkGLSVariationFilterBase();
  ~vtkGLSVariationFilterBase() override;

  /// The weights must be valid (see WTau). Filters that check more call this first.
  bool CheckParameters(vtkGLSRun& run) override;

  /// The weights as the core takes them.
  gls::VariationWeights Weights() const;

  /// The request of a filter that needs nu only (ReduceVariation): an upstream GLSGeometricVariation will do, else
  /// the derivatives, stored or fitted; stored arrays only when `mayReuseInput`.
  static SampleRequest VariationRequest(bool mayReuseInput);

  /// Maps a point's nu at the run's scales (one value per scale) to one value; called concurrently, read-only.
  using VariationReducer = std::function<double(const double* nu)>;

  /// Reduces every point's nu over the scales to one value in `out` (one per point of this piece), for the
  /// filters that summarize nu per point: from an upstream GLSGeometricVariation when the run found one
  /// (SampleRequest::VariationWillDo), else from the samples, in a fused pass that stores nothing per scale.
  /// Progress runs from 0 to progressEnd. Returns false if aborted (`out` is then incomplete).
  bool ReduceVariation(vtkGLSRun& run, const VariationReducer& reduce, double* out, double progressEnd);

  double WTau;
  double WEta;
  double WKappa;

private:
  vtkGLSVariationFilterBase(const vtkGLSVariationFilterBase&) = delete;
  void operator=(const vtkGLSVariationFilterBase&) = delete;
};

#endif
