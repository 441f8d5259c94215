// Names of the arrays the GLS filters read and write (one place, so that filters can find each other's outputs).
// The per-scale descriptors of vtkGLSScaleSpace (GLSTau, GLSEta, ...) are named in their table, vtkGLSDescriptors.h.
#ifndef vtkGLSArrayNames_h
#define vtkGLSArrayNames_h

#include "gls/LasFile.h" // the LAS attributes' names

namespace vtkGLSArrayNames
{
constexpr const char* Normals = "Normals";
constexpr const char* NormalQuality = "NormalQuality";     // normal estimation: spread of the neighbourhood
constexpr const char* NormalNeighbors = "NormalNeighbors"; // normal estimation: neighbours used
constexpr const char* NormalRadius = "GLSNormalRadius";    // field data: the radius of a RADIUS estimate (length)
constexpr const char* Scales = "GLSScales";              // field data: the absolute scales (length)
constexpr const char* KappaMedian = "GLSKappaMedian"; // scale space: median of kappa over the defined scales
constexpr const char* Variation = "GLSGeometricVariation";
constexpr const char* PertinentScaleCount = "GLSPertinentScaleCount";
constexpr const char* PertinentScales = "GLSPertinentScales";
constexpr const char* Feature = "GLSFeature";
// The scale summary of the continuous features (ScaleSummary on; gls::ScaleSummary): one value per point.
constexpr const char* StableScale = "GLSStableScale";             // the most stable scale (length)
constexpr const char* StableTau = "GLSStableTau";                 // tau there (length)
constexpr const char* StableKappa = "GLSStableKappa";             // kappa there (1/length)
constexpr const char* StablePhi = "GLSStablePhi";                 // phi there (dimensionless)
constexpr const char* MaxVariation = "GLSMaxVariation";           // the largest nu (dimensionless)
constexpr const char* MaxVariationScale = "GLSMaxVariationScale"; // its scale (length)
// The steadiest principal directions (vtkGLSPrincipalDirections; gls::StableDirection): one value per point.
constexpr const char* StableDirectionScale = "GLSStableDirectionScale"; // where d1 turns least (length)
constexpr const char* DirectionTurnRate = "GLSDirectionTurnRate";       // how much it turns (radians per log t)
constexpr const char* Anisotropy = "GLSAnisotropy";                     // (k1 - k2) / (|k1| + |k2|) there
constexpr const char* StableShapeIndex = "GLSStableShapeIndex";         // the shape index there
constexpr const char* StableDirection = "GLSStableDirection";           // d1 there (3 components, unit)
constexpr const char* RidgeValley = "GLSRidgeValley";                   // +1 ridge, -1 valley, 0 neither
// vtkGLSPrincipalDirections' DirectionScale: the principal curvatures at one chosen scale, for glyphs.
constexpr const char* DirectionScale = "GLSDirectionScale";             // field data: that scale (length)
constexpr const char* DirectionAtScale1 = "GLSPrincipalDirection1AtScale"; // d1 there (3 components, unit)
constexpr const char* DirectionAtScale2 = "GLSPrincipalDirection2AtScale"; // d2 there (3 components, unit)
constexpr const char* K1AtScale = "GLSK1AtScale";                       // k1 there (1/length)
constexpr const char* K2AtScale = "GLSK2AtScale";                       // k2 there (1/length)
constexpr const char* Sigma = "GLSSigma";                 // field data of the features: the sigma used
constexpr const char* Dissimilarity = "GLSDissimilarity";
constexpr const char* Similar = "GLSSimilar";
constexpr const char* Evaluation = "GLSEvaluation";      // field data: "Exact" or "Multiresolution"
constexpr const char* Accuracy = "GLSAccuracy";          // field data of a multi-resolution fit: its epsilon
constexpr const char* Backend = "GLSBackend";            // field data: "CPU" or "CUDA", where the fits ran
constexpr const char* QueryPointId = "GLSQueryPointId";   // field data of the dissimilarity output
constexpr const char* GhostPoints = "GLSGhostPoints";     // field data of a distributed run: ghosts this rank used
constexpr const char* StrayPoints = "GLSStrayPoints";     // field data: stray points left out (NaN results)
constexpr const char* Stray = "GLSStray";                 // point data, when some were: 1 at the stray points
constexpr const char* MinimumNeighbors = "GLSMinimumNeighbors"; // field data: the MinimumNeighbors a fit applied
constexpr const char* Tiles = "GLSTiles";                 // field data: spatial tiles of a fit cut to its MemoryBudget
constexpr const char* CompactNormals = "GLSCompactNormals"; // field data: 1 where a fit kept its normals compact
constexpr const char* CoincidentPoints = "GLSCoincidentPoints"; // field data: input points merged into another
constexpr const char* NonFinitePoints = "GLSNonFinitePoints"; // field data: points with a non-finite coordinate
constexpr const char* AutomaticArray = "(automatic)"; // an array selection that lets the filter choose
constexpr const char* Bandwidth = "GLSBandwidth";          // adaptive bandwidth (length)
constexpr const char* RawBandwidth = "GLSRawBandwidth";    // adaptive bandwidth before smoothing (length)
constexpr const char* Displacement = "GLSDisplacement";    // projection: distance moved (length)
constexpr const char* ProjectionIterations = "GLSProjectionIterations"; // projection: fits made per point
constexpr const char* Colors = gls::lasname::Rgb;          // readers: colours (0-255 text, 0-65535 LAS; VTK's PLY
                                                           // reader's name)
constexpr const char* ScannerPosition = "ScannerPosition"; // readers: the scanner that saw a point (point data: PTX)
                                                           // or every point (field data, one tuple: a PCD's VIEWPOINT)
constexpr const char* Orientation = "GLSOrientation";      // field data of the normal estimation: how it oriented
// The LAS reader's attributes that other filters read (the lidar evidence of the Automatic orientation): named in
// the table of gls/LasFile.h (forEachLasAttribute).
constexpr const char* ScanAngle = gls::lasname::ScanAngle;             // degrees from nadir
constexpr const char* NumberOfReturns = gls::lasname::NumberOfReturns; // returns of the point's pulse
constexpr const char* Classification = gls::lasname::Classification;   // the ASPRS class (2: ground)
// LAS reader, field data: the file's coordinate system (OGC WKT; GeoTIFF keys), its scale and offset (3 each: a
// position is X scale + offset), the withheld points left out.
constexpr const char* CoordinateSystemWKT = "CoordinateSystemWKT";
constexpr const char* GeoKeyDirectory = "GeoKeyDirectory";
constexpr const char* GeoDoubleParams = "GeoDoubleParams";
constexpr const char* GeoAsciiParams = "GeoAsciiParams";
constexpr const char* LasScale = "LasScale";
constexpr const char* LasOffset = "LasOffset";
constexpr const char* WithheldPoints = "GLSWithheldPoints";
constexpr const char* Intensity = gls::lasname::Intensity; // readers: a scanner's return intensity
}

#endif
