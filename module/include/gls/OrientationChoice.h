// Which side of the surface a normal faces, decided from what a scan's file says of how it was taken: the one place
// that rule lives (the Automatic orientation of the normal estimation, and through it the main job).
//
//   1. Each point's own scanner position (PTX scans, merged scans: a per-point array): each normal faces its scanner.
//   2. One sensor position for the whole file (a PCD's VIEWPOINT, PCL's default origin included): every normal faces
//      that point.
//   3. Airborne lidar (a LAS/LAZ file's attributes show it, lidarLooksAirborne): up, the walls along the minimum
//      spanning tree (NormalOrientation::UpAlongSpanningTree).
//   4. Other lidar (a LAS/LAZ file's attributes without those signs: a terrestrial or indoor scan exported as LAS):
//      the minimum spanning tree with each component's ground or floor facing up (GroundUpAlongSpanningTree): walls
//      and ceilings are not forced up (a room's ceiling faces down, into it).
//   5. Otherwise the minimum spanning tree (outward from each component's farthest point; terrain-like clouds up).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace gls
{

/// How many points of a lidar file show each sign of an airborne acquisition. Counts (doubles, so that pieces of a
/// distributed cloud can add them); an attribute the file lacks has no count (the has* flags).
struct LidarEvidence
{
  double points = 0.0;          ///< the points counted (finite positions)
  bool hasScanAngle = false;    ///< a ScanAngle (degrees from nadir) per point
  double nonZeroAngle = 0.0;    ///< |scan angle| >= 0.5 degree: the file records them (terrestrial exports write 0)
  double angleBeyondSwath = 0.0; ///< |scan angle| > kAirborneSwathDegrees (or not finite): no aircraft's swath
  bool hasReturns = false;      ///< a NumberOfReturns per point
  double multipleReturns = 0.0; ///< NumberOfReturns > 1: pulses that passed through vegetation
  bool hasClasses = false;      ///< an ASPRS Classification per point
  double ground = 0.0;          ///< class 2 (ground): the file was classified for terrain

  LidarEvidence& operator+=(const LidarEvidence& other);
};

/// The widest scan angle (degrees from nadir) of an airborne scanner's swath; an angle beyond it is no aircraft's.
constexpr double kAirborneSwathDegrees = 75.0;
/// The smallest share of the points that makes an attribute's sign count (1%): a few stray values do not.
constexpr double kAirborneEvidenceShare = 0.01;

/// Adds n points' attributes to `evidence` (any pointer may be null: that attribute is not in the file). Only the
/// points whose `finite` flag is set count (null: every point).
void countLidarEvidence(const float* scanAngle, const std::uint8_t* numberOfReturns, const std::uint8_t* classification,
  const unsigned char* finite, std::size_t n, LidarEvidence& evidence);

/// Whether the attributes say airborne lidar: scan angles recorded (at least kAirborneEvidenceShare of the points off
/// nadir) and all of them within an aircraft's swath, or multiple returns, or ground classified (each at least
/// kAirborneEvidenceShare of the points). `why` receives the signs found, e.g. "scan angles recorded at 94% of the
/// points; 26% with multiple returns; 26% classified ground", or why not.
bool lidarLooksAirborne(const LidarEvidence& evidence, std::string& why);

/// The orientations the rule chooses from (the normal estimation maps each to its own mode).
enum class OrientationSource
{
  ScannerPositions,     ///< towards each point's own scanner position
  SensorPosition,       ///< towards the file's one sensor position
  Airborne,             ///< NormalOrientation::UpAlongSpanningTree
  Terrestrial,          ///< NormalOrientation::GroundUpAlongSpanningTree
  MinimumSpanningTree   ///< NormalOrientation::MinimumSpanningTree
};

struct OrientationChoice
{
  OrientationSource source = OrientationSource::MinimumSpanningTree;
  std::string reason; ///< what it is and why, for a log and the field data, e.g. "up, the walls along the minimum
                      ///< spanning tree: airborne lidar (scan angles recorded at 94% of the points; ...)"
};

/// The rule above. `sensor` (3 values, or null) is the file's one sensor position.
OrientationChoice chooseOrientation(bool scannerPositions, const double* sensor, const LidarEvidence& evidence);

} // namespace gls
