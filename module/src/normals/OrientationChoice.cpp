#include "gls/OrientationChoice.h"

#include <cmath>
#include <sstream>

namespace gls
{

LidarEvidence& LidarEvidence::operator+=(const LidarEvidence& other)
{
  this->points += other.points;
  this->hasScanAngle = this->hasScanAngle || other.hasScanAngle;
  this->nonZeroAngle += other.nonZeroAngle;
  this->angleBeyondSwath += other.angleBeyondSwath;
  this->hasReturns = this->hasReturns || other.hasReturns;
  this->multipleReturns += other.multipleReturns;
  this->hasClasses = this->hasClasses || other.hasClasses;
  this->ground += other.ground;
  return *this;
}

void countLidarEvidence(const float* scanAngle, const std::uint8_t* numberOfReturns, const std::uint8_t* classification,
  const unsigned char* finite, std::size_t n, LidarEvidence& evidence)
{
  evidence.hasScanAngle = evidence.hasScanAngle || scanAngle != nullptr;
  evidence.hasReturns = evidence.hasReturns || numberOfReturns != nullptr;
  evidence.hasClasses = evidence.hasClasses || classification != nullptr;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (finite && !finite[i])
    {
      continue;
    }
    evidence.points += 1.0;
    if (scanAngle)
    {
      const double a = std::abs(static_cast<double>(scanAngle[i]));
      evidence.nonZeroAngle += a >= 0.5 ? 1.0 : 0.0;
      evidence.angleBeyondSwath += a <= kAirborneSwathDegrees ? 0.0 : 1.0; // NaN included
    }
    if (numberOfReturns)
    {
      evidence.multipleReturns += numberOfReturns[i] > 1 ? 1.0 : 0.0;
    }
    if (classification)
    {
      evidence.ground += classification[i] == 2 ? 1.0 : 0.0;
    }
  }
}

namespace
{

/// "94%" (or "0.3%") of a share.
std::string percent(double share)
{
  std::ostringstream s;
  s.precision(share >= 0.1 ? 3 : 2);
  s << 100.0 * share << "%";
  return s.str();
}

} // namespace

bool lidarLooksAirborne(const LidarEvidence& e, std::string& why)
{
  why.clear();
  if (!(e.points > 0.0) || !(e.hasScanAngle || e.hasReturns || e.hasClasses))
  {
    why = "no lidar attributes (scan angle, returns, classification)";
    return false;
  }
  const double least = kAirborneEvidenceShare * e.points;
  std::ostringstream found;
  const auto add = [&found](const std::string& what) { found << (found.tellp() > 0 ? "; " : "") << what; };
  const bool angles = e.hasScanAngle && e.nonZeroAngle >= least && e.angleBeyondSwath == 0.0;
  if (angles)
  {
    add("scan angles recorded at " + percent(e.nonZeroAngle / e.points) + " of the points, all within an aircraft's "
        "swath");
  }
  const bool returns = e.hasReturns && e.multipleReturns >= least;
  if (returns)
  {
    add(percent(e.multipleReturns / e.points) + " of the points with multiple returns");
  }
  const bool ground = e.hasClasses && e.ground >= least;
  if (ground)
  {
    add(percent(e.ground / e.points) + " of the points classified ground");
  }
  if (angles || returns || ground)
  {
    why = found.str();
    return true;
  }
  why = "no scan angles off nadir within a swath, no multiple returns, no ground class";
  return false;
}

OrientationChoice chooseOrientation(bool scannerPositions, const double* sensor, const LidarEvidence& evidence)
{
  OrientationChoice choice;
  if (scannerPositions)
  {
    choice.source = OrientationSource::ScannerPositions;
    choice.reason = "towards each point's scanner (the file's scanner positions)";
    return choice;
  }
  if (sensor)
  {
    std::ostringstream s;
    s.precision(10);
    s << "towards the sensor at (" << sensor[0] << ", " << sensor[1] << ", " << sensor[2]
      << ") (the file's sensor position)";
    choice.source = OrientationSource::SensorPosition;
    choice.reason = s.str();
    return choice;
  }
  std::string why;
  if (lidarLooksAirborne(evidence, why))
  {
    choice.source = OrientationSource::Airborne;
    choice.reason = "up, the walls along the minimum spanning tree: airborne lidar (" + why + ")";
    return choice;
  }
  if (evidence.hasScanAngle || evidence.hasReturns || evidence.hasClasses)
  {
    choice.source = OrientationSource::Terrestrial;
    choice.reason = "minimum spanning tree, the ground or floor up: terrestrial lidar (" + why + ")";
    return choice;
  }
  choice.source = OrientationSource::MinimumSpanningTree;
  choice.reason = "minimum spanning tree, outward (the file gives no sensor position and no lidar attributes)";
  return choice;
}

} // namespace gls
