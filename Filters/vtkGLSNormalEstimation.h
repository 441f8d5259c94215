/**
 * @class   vtkGLSNormalEstimation
 * @brief   PCA point normals with orientation, the first step of a GLS pipeline.
 *
 * The normal of a point is the eigenvector of the smallest eigenvalue of the covariance of its neighbourhood: the
 * NumberOfNeighbors nearest points (NeighborhoodType K_NEAREST, default, the point itself included) or every point
 * closer than Radius (RADIUS, a length in the input's units). Computed in double precision in local coordinates,
 * on NumberOfThreads threads (bitwise identical results for any count).
 *
 * Orientation (PCA gives a direction, not a side):
 * - NONE: the eigen solver's sign (deterministic but not consistent).
 * - TOWARDS_POINT / AWAY_FROM_POINT: facing OrientationPoint (e.g. the scanner position) or away from it.
 * - MINIMUM_SPANNING_TREE (default): Hoppe et al. 1992; the orientation is propagated along the minimum spanning tree
 *   of the GraphNeighbors-nearest-neighbour graph with cost 1 - |n_i . n_j|; every connected component starts from
 *   its point farthest from its centroid, oriented away from the centroid (outward on closed shapes).
 * - AGREE_WITH_EXISTING: flipped to agree with the normals selected by SetInputArrayToProcess(0, ...) (default: the
 *   active normals), e.g. a scanner's normals whose length or accuracy is poor; points whose existing normal is not
 *   finite keep the solver's sign.
 *
 * Output: the input with point-data array `Normals` (3 components, unit, dimensionless), set as the active normals
 * (replacing any previous active normals).
 * Degenerate input: a point with fewer than 3 neighbours, whose neighbours lie on a line, or with non-finite
 * coordinates gets a NaN normal (later GLS filters leave it out of every neighbourhood). An empty input, a Radius <= 0
 * in RADIUS mode, or AGREE_WITH_EXISTING without a valid normals array is an error.
 *
 * Distributed runs (pvbatch / pvserver on N MPI ranks; the Controller has several processes): each rank fetches the
 * other ranks' points within the reach of its neighbourhoods (Radius, or the largest distance from one of its points
 * to its k-th nearest point in its own piece, which bounds the true one) around its piece (vtkGLSDistributedCloud),
 * estimates the normals of its own points only, and orients them per point (TOWARDS/AWAY_FROM_POINT,
 * AGREE_WITH_EXISTING) or, for MINIMUM_SPANNING_TREE, by gathering the points and unoriented normals on rank 0
 * (ordered by global id: the GlobalIds attribute, else rank order), orienting them there as a serial run would, and
 * sending every rank its oriented normals back (rank 0 then holds 56 bytes per point of the whole cloud). The
 * normals equal a serial run's (sign included). A planar input (every point in one plane z = const, possibly a 2D
 * curve) is refused on several processes: its curve test is global.
 */
#ifndef vtkGLSNormalEstimation_h
#define vtkGLSNormalEstimation_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSFilterBase.h"

#include <vector> // for std::vector

namespace gls
{
struct NormalEstimationSettings;
struct NormalEstimationResult;
}

class VTKGLSFILTERS_EXPORT vtkGLSNormalEstimation : public vtkGLSFilterBase
{
public:
  static vtkGLSNormalEstimation* New();
  vtkTypeMacro(vtkGLSNormalEstimation, vtkGLSFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum NeighborhoodTypes
  {
    K_NEAREST = 0,
    RADIUS = 1
  };
  enum OrientationModes
  {
    NONE = 0,
    TOWARDS_POINT = 1,
    AWAY_FROM_POINT = 2,
    MINIMUM_SPANNING_TREE = 3,
    AGREE_WITH_EXISTING = 4
  };

  ///@{
  /// K_NEAREST (default) or RADIUS.
  vtkSetClampMacro(NeighborhoodType, int, K_NEAREST, RADIUS);
  vtkGetMacro(NeighborhoodType, int);
  void SetNeighborhoodTypeToKNearest() { this->SetNeighborhoodType(K_NEAREST); }
  void SetNeighborhoodTypeToRadius() { this->SetNeighborhoodType(RADIUS); }
  ///@}

  ///@{
  /// Neighbours of the K_NEAREST neighbourhood, the point included (default 16, at least 3).
  vtkSetClampMacro(NumberOfNeighbors, int, 3, 100000);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /// Radius of the RADIUS neighbourhood (length, input units; must be > 0 in that mode). Default 0.
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// Orientation mode (default MINIMUM_SPANNING_TREE).
  vtkSetClampMacro(Orientation, int, NONE, AGREE_WITH_EXISTING);
  vtkGetMacro(Orientation, int);
  void SetOrientationToNone() { this->SetOrientation(NONE); }
  void SetOrientationToTowardsPoint() { this->SetOrientation(TOWARDS_POINT); }
  void SetOrientationToAwayFromPoint() { this->SetOrientation(AWAY_FROM_POINT); }
  void SetOrientationToMinimumSpanningTree() { this->SetOrientation(MINIMUM_SPANNING_TREE); }
  void SetOrientationToAgreeWithExisting() { this->SetOrientation(AGREE_WITH_EXISTING); }
  ///@}

  ///@{
  /// The point of TOWARDS_POINT / AWAY_FROM_POINT (input coordinates, default origin).
  vtkSetVector3Macro(OrientationPoint, double);
  vtkGetVector3Macro(OrientationPoint, double);
  ///@}

  ///@{
  /// k of the nearest-neighbour graph of MINIMUM_SPANNING_TREE (default 10, at least 1).
  vtkSetClampMacro(GraphNeighbors, int, 1, 1000);
  vtkGetMacro(GraphNeighbors, int);
  ///@}

protected:
  vtkGLSNormalEstimation();
  ~vtkGLSNormalEstimation() override;

  int Execute(vtkGLSRun& run) override;

  /// The distributed estimate (see the class documentation): ghosts, normals of the owned points, and the
  /// minimum-spanning-tree orientation on rank 0. The run's cloud and `reference` are scratch. False (with an
  /// error) on a communication failure.
  bool EstimateDistributed(vtkGLSRun& run, std::vector<double>& reference, gls::NormalEstimationSettings settings,
    gls::NormalEstimationResult& result);

  int NeighborhoodType;
  int NumberOfNeighbors;
  double Radius;
  int Orientation;
  double OrientationPoint[3];
  int GraphNeighbors;

private:
  vtkGLSNormalEstimation(const vtkGLSNormalEstimation&) = delete;
  void operator=(const vtkGLSNormalEstimation&) = delete;
};

#endif
