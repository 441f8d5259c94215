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
 * - AUTOMATIC (default): what the file says of how it was scanned decides (gls::chooseOrientation, the one place of
 *   that rule; docs/normals.md): each point's own scanner position, a point array `ScannerPosition` (PTX scans,
 *   merged scans) -> TOWARDS_VIEWPOINT_ARRAY with it; else the file's one sensor position, a field-data array
 *   `ScannerPosition` (a PCD's VIEWPOINT) -> TOWARDS_POINT it; else airborne lidar, as the point arrays `ScanAngle`,
 *   `NumberOfReturns` and `Classification` of a LAS file show it (scan angles recorded within a swath, multiple
 *   returns, or ground classified, each at 1% of the points or more) -> UP_ALONG_SPANNING_TREE; else, with those
 *   arrays (a terrestrial or indoor scan exported as LAS) -> GROUND_UP_ALONG_SPANNING_TREE; else
 *   MINIMUM_SPANNING_TREE. The choice and why go to the field data `GLSOrientation` (every mode writes what it did).
 * - NONE: the eigen solver's sign (deterministic but not consistent).
 * - TOWARDS_POINT / AWAY_FROM_POINT: facing OrientationPoint (e.g. the scanner position) or away from it.
 * - MINIMUM_SPANNING_TREE: Hoppe et al. 1992; the orientation is propagated along the minimum spanning tree
 *   of the GraphNeighbors-nearest-neighbour graph with cost 1 - |n_i . n_j|; every connected component starts from
 *   its point farthest from its centroid, oriented away from the centroid (outward on closed shapes); then, on a
 *   terrain-like cloud (its height at most half its smaller horizontal extent, its components' normals with a mean
 *   z of size at least 0.7: gls::kTerrainCoherence), the components facing down are turned to face up, +z (an
 *   aerial tile is not oriented into the ground; a closed surface's normals sum to about 0 and keep their sides).
 * - UP: every normal facing UpDirection (default +z), point by point (aerial scans; PDAL's always_up).
 * - UP_ALONG_SPANNING_TREE: airborne lidar. The normals within 72.5 degrees of UpDirection (ground, roofs, slopes)
 *   face it point by point; the steeper ones (walls) agree with their neighbours along the minimum spanning tree,
 *   each connected component turned so that its upward normals face up: a building's walls face out, as its roof and
 *   the ground around it do, where UP would give each wall point a random side.
 * - GROUND_UP_ALONG_SPANNING_TREE: terrestrial lidar (a scanner standing on the ground or a floor). The minimum
 *   spanning tree, each connected component turned so that its ground faces UpDirection: the lowest near-horizontal
 *   normals (within 25.8 degrees of UpDirection) of each column of a 64 x 64 grid over the cloud. Nothing else is
 *   forced: a room's ceiling faces down into the room and its walls in, a building's walls face out.
 * - AGREE_WITH_EXISTING: flipped to agree with the normals selected by SetInputArrayToProcess(0, ...) (default: the
 *   active normals), e.g. a scanner's normals whose length or accuracy is poor; points whose existing normal is not
 *   finite keep the solver's sign. A per-point view direction (from the point towards its scanner) is such an array.
 * - TOWARDS_VIEWPOINT_ARRAY: facing each point's own viewpoint, the position of the scanner that saw it, read from
 *   the point array selected by SetInputArrayToProcess(1, ...) (3 components, floating point, input coordinates;
 *   merged scans carry it). Points whose viewpoint is not finite keep the solver's sign.
 * A non-finite OrientationPoint (TOWARDS_POINT, AWAY_FROM_POINT) or UpDirection (UP, UP_ALONG_SPANNING_TREE) is an
 * error naming the property.
 *
 * Degenerate neighbourhoods (gls/NormalEstimation.h): the spread of a neighbourhood is its middle covariance
 * eigenvalue over the largest, 0 on a line, 1 when isotropic in the tangent plane. Scanner sampling (dense along scan
 * lines, sparse across) and the rings of a UV sphere near its poles give k-nearest neighbourhoods that are nearly
 * lines, and a small radius can hold three points on an arc; their PCA "normal" is wrong by up to 90 degrees. A
 * neighbourhood with a spread below MinimumSpread grows (twice the neighbours, or sqrt(2) times the radius, per
 * step) up to MaximumGrowth times the neighbours; where none spans two dimensions the normal is NaN, with one
 * warning giving the count. Points with fewer than 3 neighbours or non-finite coordinates get NaN too (later GLS
 * filters leave them out of every neighbourhood). A planar 2D curve is not grown (its normals are in its plane).
 *
 * Coincident points (bitwise-equal coordinates, e.g. an OBJ reader's per-corner vertices) are merged before the
 * neighbourhoods are formed (each position counted once; a warning gives the count and field data
 * GLSCoincidentPoints records it); every copy receives its position's normal.
 *
 * Output: the input with point-data arrays `Normals` (3 components, unit, dimensionless), set as the active normals
 * (replacing any previous active normals), `NormalQuality` (the spread of the neighbourhood used, dimensionless in
 * [0, 1]; threshold it to see where the normals are weak; NaN with fewer than 3 neighbours) and `NormalNeighbors`
 * (the neighbours used, after any growth). In RADIUS mode the field data `GLSNormalRadius` records the radius used.
 * OutputPrecision SINGLE_PRECISION writes Normals and NormalQuality as float32 (half their memory, for clouds of 10^8
 * points). Before any work the estimation's memory (the larger of gls::normalEstimationBytes, beside the filter's
 * copy of the points where it keeps it, and the result beside the outputs: about 141 bytes a point at the defaults,
 * 137 measured at 10M points) is checked against MemoryBudget;
 * above it the filter stops with an error saying how much it needs. An empty input, a negative or non-finite Radius, or AGREE_WITH_EXISTING without a valid normals array is
 * an error.
 *
 * Distributed runs (pvbatch / pvserver on N MPI ranks; the Controller has several processes): each rank fetches the
 * other ranks' points within the reach of its neighbourhoods (Radius, or the largest distance from one of its points
 * to its k-th nearest point in its own piece, which bounds the true one) around its piece (vtkGLSDistributedCloud),
 * estimates the normals of its own points only, and orients them per point (TOWARDS/AWAY_FROM_POINT,
 * AGREE_WITH_EXISTING, UP) or, for MINIMUM_SPANNING_TREE and UP_ALONG_SPANNING_TREE, by gathering the points and
 * unoriented normals on rank 0
 * (ordered by global id: the GlobalIds attribute, else rank order), orienting them there as a serial run would, and
 * sending every rank its oriented normals back (rank 0 then holds 56 bytes per point of the whole cloud). The
 * normals equal a serial run's (sign included). A planar input (every point in one plane z = const, possibly a 2D
 * curve) is refused on several processes: its curve test is global.
 */
#ifndef vtkGLSNormalEstimation_h
#define vtkGLSNormalEstimation_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSFilterBase.h"

#include <string> // for std::string
#include <vector> // for std::vector

namespace gls
{
struct NormalEstimationSettings;
struct NormalEstimationResult;
struct ParallelOptions;
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
  enum RefinementModes
  {
    NO_REFINEMENT = 0,
    GLS_REFINEMENT = 1
  };
  enum OrientationModes
  {
    NONE = 0,
    TOWARDS_POINT = 1,
    AWAY_FROM_POINT = 2,
    MINIMUM_SPANNING_TREE = 3,
    AGREE_WITH_EXISTING = 4,
    TOWARDS_VIEWPOINT_ARRAY = 5,
    UP = 6,
    UP_ALONG_SPANNING_TREE = 7,
    AUTOMATIC = 8,
    GROUND_UP_ALONG_SPANNING_TREE = 9
  };

  ///@{
  /// K_NEAREST (default) or RADIUS.
  vtkSetMacro(NeighborhoodType, int);
  vtkGetMacro(NeighborhoodType, int);
  void SetNeighborhoodTypeToKNearest() { this->SetNeighborhoodType(K_NEAREST); }
  void SetNeighborhoodTypeToRadius() { this->SetNeighborhoodType(RADIUS); }
  ///@}

  ///@{
  /// Neighbours of the K_NEAREST neighbourhood, the point included (default 16, at least 3).
  vtkSetMacro(NumberOfNeighbors, int);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /// Radius of the RADIUS neighbourhood (length, input units). Default 0: automatic, the median distance from a
  /// point to its NumberOfNeighbors-th nearest point (over up to 10,000 points at a regular stride), so that the
  /// ball holds about NumberOfNeighbors points. Negative or non-finite: an error in RADIUS mode.
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// Refinement of the oriented normals: NO_REFINEMENT (default, the PCA normals) or GLS_REFINEMENT, where each
  /// normal becomes eta of the GLS oriented-sphere fit of its neighbours' points and (PCA, oriented) normals at the
  /// scale RefinementScale times the distance to the farthest neighbour its PCA used: the sphere follows the
  /// curvature that the PCA plane ignores. A point whose fit is undefined keeps its PCA normal. In a distributed run
  /// each piece fetches the oriented normals of the points within its largest refinement scale (a second ghost
  /// exchange), so the result equals the serial one.
  vtkSetMacro(Refinement, int);
  vtkGetMacro(Refinement, int);
  void SetRefinementToNone() { this->SetRefinement(NO_REFINEMENT); }
  void SetRefinementToGLS() { this->SetRefinement(GLS_REFINEMENT); }
  ///@}

  ///@{
  /// The scale of the GLS refinement, as a factor on each point's PCA neighbourhood radius (dimensionless, default
  /// 1.5, from 0.5 to 10).
  vtkSetMacro(RefinementScale, double);
  vtkGetMacro(RefinementScale, double);
  ///@}

  ///@{
  /// The spread (middle over largest covariance eigenvalue) below which a neighbourhood is degenerate and grows;
  /// dimensionless in [0, 1], default 0.05. 0 treats only exact lines as degenerate.
  vtkSetMacro(MinimumSpread, double);
  vtkGetMacro(MinimumSpread, double);
  ///@}

  ///@{
  /// The largest factor on the neighbour count when a degenerate neighbourhood grows (the k of K_NEAREST is doubled,
  /// the Radius multiplied by sqrt(2), per step), default 8 (three steps: 128 neighbours for the default 16);
  /// 1 = no growth (degenerate neighbourhoods give NaN at once). A distributed run's ghost band covers the grown
  /// neighbourhoods.
  vtkSetMacro(MaximumGrowth, double);
  vtkGetMacro(MaximumGrowth, double);
  ///@}

  ///@{
  /// Orientation mode (default AUTOMATIC: from what the file says, see the class documentation).
  vtkSetMacro(Orientation, int);
  vtkGetMacro(Orientation, int);
  void SetOrientationToAutomatic() { this->SetOrientation(AUTOMATIC); }
  void SetOrientationToUpAlongSpanningTree() { this->SetOrientation(UP_ALONG_SPANNING_TREE); }
  void SetOrientationToGroundUpAlongSpanningTree() { this->SetOrientation(GROUND_UP_ALONG_SPANNING_TREE); }
  void SetOrientationToNone() { this->SetOrientation(NONE); }
  void SetOrientationToTowardsPoint() { this->SetOrientation(TOWARDS_POINT); }
  void SetOrientationToAwayFromPoint() { this->SetOrientation(AWAY_FROM_POINT); }
  void SetOrientationToMinimumSpanningTree() { this->SetOrientation(MINIMUM_SPANNING_TREE); }
  void SetOrientationToAgreeWithExisting() { this->SetOrientation(AGREE_WITH_EXISTING); }
  void SetOrientationToTowardsViewpointArray() { this->SetOrientation(TOWARDS_VIEWPOINT_ARRAY); }
  void SetOrientationToUp() { this->SetOrientation(UP); }
  ///@}

  ///@{
  /// The direction of UP, UP_ALONG_SPANNING_TREE and GROUND_UP_ALONG_SPANNING_TREE orientation (input coordinates,
  /// any length but 0; default 0, 0, 1; AUTOMATIC's lidar rules take +z). Not finite or zero is an error.
  vtkSetVector3Macro(UpDirection, double);
  vtkGetVector3Macro(UpDirection, double);
  ///@}

  ///@{
  /// The point of TOWARDS_POINT / AWAY_FROM_POINT (input coordinates, default origin; not finite: an error).
  vtkSetVector3Macro(OrientationPoint, double);
  vtkGetVector3Macro(OrientationPoint, double);
  ///@}

  ///@{
  /// k of the nearest-neighbour graph of MINIMUM_SPANNING_TREE (default 10, at least 1).
  vtkSetMacro(GraphNeighbors, int);
  vtkGetMacro(GraphNeighbors, int);
  ///@}

  ///@{
  /// The type of Normals and NormalQuality: vtkAlgorithm::DOUBLE_PRECISION (default: doubles) or
  /// vtkAlgorithm::SINGLE_PRECISION (float32, each value rounded to nearest from the double computed, a relative
  /// 6e-8: 16 bytes a point instead of 32). Another value is refused (an error, nothing computed).
  vtkSetMacro(OutputPrecision, int);
  vtkGetMacro(OutputPrecision, int);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSNormalEstimation();
  ~vtkGLSNormalEstimation() override;

  int Execute(vtkGLSRun& run) override;

  /// The run's own refusals (a bad or, on several processes, automatic Radius; a planar distributed input), with an
  /// error; false then.
  bool CheckRun(const vtkGLSRun& run);

  /// Whether the run frees its copy of the points once the core's grid holds its own (serial, without the GLS
  /// refinement).
  bool FreesPointsEarly(const vtkGLSRun& run) const;
  /// The bytes this piece's estimation holds at once (the larger of the core's peak, gls::normalEstimationBytes,
  /// and its result beside the outputs; its copy of the points where it keeps it, the reference normals), checked
  /// against MemoryBudget before any work.
  double NeededBytes(const vtkGLSRun& run, const gls::NormalEstimationSettings& settings,
    const std::vector<double>& reference) const;
  /// How a run orients: the mode (AUTOMATIC resolved), its point or direction, the viewpoint array it reads, and
  /// what it did for the field data GLSOrientation.
  struct OrientationPlan
  {
    int Mode = MINIMUM_SPANNING_TREE;
    double Point[3] = { 0.0, 0.0, 0.0 }; ///< TOWARDS_POINT / AWAY_FROM_POINT
    double Up[3] = { 0.0, 0.0, 1.0 };    ///< UP / UP_ALONG_SPANNING_TREE
    std::string ViewpointArray;          ///< TOWARDS_VIEWPOINT_ARRAY by AUTOMATIC: the array's name ("": selected)
    std::string Report;
  };
  /// The run's orientation: the properties checked (a non-finite OrientationPoint or UpDirection, a zero UpDirection:
  /// false, with an error naming it), and AUTOMATIC's choice (ChooseOrientation). Collective.
  bool PlanOrientation(const vtkGLSRun& run, OrientationPlan& plan);
  /// AUTOMATIC's choice from the input's arrays: gls::chooseOrientation of its ScannerPosition point or field-data
  /// array and its lidar attributes (counted over its finite points, summed over every process). Collective.
  void ChooseOrientation(const vtkGLSRun& run, OrientationPlan& plan);
  /// The core's settings from the properties and the plan.
  void ResolveSettings(const vtkGLSRun& run, const OrientationPlan& plan, gls::NormalEstimationSettings& settings);
  /// AGREE_WITH_EXISTING and TOWARDS_VIEWPOINT_ARRAY: the reference directions of every point (the selected normals,
  /// or the directions to each point's viewpoint) and the orientation that follows them; false, with an error, when
  /// the selected array is missing here or on another process. Nothing for the other orientations.
  bool GatherReference(const vtkGLSRun& run, const OrientationPlan& plan, std::vector<double>& reference,
    gls::NormalEstimationSettings& settings);
  /// The serial estimate: coincident points merged, the automatic radius measured, the normals, their GLS
  /// refinement. COMPLETED, FAILED (with an error) or ABORTED.
  int EstimateSerial(vtkGLSRun& run, std::vector<double>& reference, gls::NormalEstimationSettings& settings,
    gls::NormalEstimationResult& result);

  /// The distributed estimate (see the class documentation): ghosts, normals of the owned points, and the
  /// minimum-spanning-tree orientation on rank 0. The run's cloud and `reference` are scratch. False (with an
  /// error) on a communication failure.
  bool EstimateDistributed(vtkGLSRun& run, std::vector<double>& reference, gls::NormalEstimationSettings& settings,
    gls::NormalEstimationResult& result);
  /// This piece's part of a distributed estimate: the ghosts within the reach of its neighbourhoods, then the normals
  /// of its owned points (unoriented when the tree orients them: OrientAcrossPieces) and their graph degrees.
  bool EstimateWithGhosts(vtkGLSRun& run, std::vector<double>& reference, gls::NormalEstimationSettings& settings,
    gls::NormalEstimationResult& result, std::vector<int>& graphDegrees);
  /// The minimum spanning tree's orientation of every piece's normals: gathered on rank 0, oriented in global-id
  /// order as a serial run would, sent back. False (with an error) on a communication failure.
  bool OrientAcrossPieces(const vtkGLSRun& run, const gls::NormalEstimationSettings& settings,
    const std::vector<int>& graphDegrees, gls::NormalEstimationResult& result);

  /// GLS refinement of a distributed estimate: the ghosts (other pieces' points within RefinementScale times this
  /// piece's largest reach) with their oriented normals, coincident positions counted once as in a serial run, then
  /// the serial refinement on the owned points (the run's threads, without progress: no abort half-way through a
  /// collective run). False (with an error) on a communication failure.
  bool RefineDistributed(
    vtkGLSRun& run, const gls::ParallelOptions& parallel, gls::NormalEstimationResult& result);

  /// Writes Normals, NormalQuality and NormalNeighbors to every input point (copies of a merged position included),
  /// the one-line warning for the points without a normal, and the field data (GLSNormalRadius, GLSOrientation, the
  /// run's).
  void WriteNormals(vtkGLSRun& run, const gls::NormalEstimationSettings& settings, const OrientationPlan& plan,
    const gls::NormalEstimationResult& result);

  int NeighborhoodType;
  int NumberOfNeighbors;
  double Radius;
  int Orientation;
  double OrientationPoint[3];
  double UpDirection[3];
  int GraphNeighbors;
  double MinimumSpread;
  double MaximumGrowth;
  int Refinement;
  double RefinementScale;
  int OutputPrecision;

private:
  vtkGLSNormalEstimation(const vtkGLSNormalEstimation&) = delete;
  void operator=(const vtkGLSNormalEstimation&) = delete;
};

#endif
