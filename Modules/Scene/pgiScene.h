/**
 * @file pgiScene.h
 * @brief Scene descriptions shared by every ProxyGI renderer: a small JSON
 * file, or the built-in default scene (the bunny over a ground plane under
 * the forest map).
 *
 * ```json
 * {
 *   "objects": [
 *     { "name": "bunny", "mesh": "meshes/bunny00.off",
 *       "translate": [0, 0, 0.39], "rotate": [90, 0, 0], "scale": 1,
 *       "albedo": [0.8, 0.8, 0.8] },
 *     { "name": "ground", "plane": { "center": [0, 0, 0], "size": 6 },
 *       "albedo": [0.5, 0.5, 0.5] },
 *     { "name": "ball", "sphere": { "center": [0, 0, 1.5], "radius": 1, "resolution": 64 } },
 *     { "name": "back wall", "quad": { "origin": [-1, 1, 0], "point1": [1, 1, 0],
 *       "point2": [-1, 1, 2], "resolution": [32, 32] } },
 *     { "name": "block", "box": { "center": [0.4, 0, 0.3], "size": [0.6, 0.6, 0.6],
 *       "resolution": 8 } }
 *   ],
 *   "environment": { "map": "environments/forest.exr", "rotation": 0, "scale": 1 },
 *   "lights": [ { "type": "sphere", "center": [2, 0, 3], "radius": 0.3, "radiance": [20, 20, 20] },
 *               { "type": "point", "position": [0, 2, 3], "intensity": [5, 5, 5] } ],
 *   "camera": { "position": [0, -4, 2], "focal_point": [0, 0, 0.4], "view_up": [0, 0, 1],
 *               "view_angle": 30, "size": [512, 512] },
 *   "effects": { "shadows": true, "indirect": true, "local_lights": true },
 *   "light_cloud": { "region": [-1, 1, -1, 1, 0, 2],
 *                    "path": [[-0.5, 0, 1.5], [0.5, 0.3, 0.8]] }
 * }
 * ```
 * A "plane" is a horizontal square; a "quad" any parallelogram (vtkPlaneSource's
 * origin and two corners: its normal is (point1 - origin) x (point2 - origin),
 * it is lit on that side), a wall; both are planes to the SH route. A "box"
 * has six faces with outward normals, each split resolution x resolution.
 * "environment" may instead be { "uniform": [r, g, b] }. Rotations are
 * degrees about x, then y, then z; the transform applies scale, rotation,
 * translation in that order. Mesh and map paths are tried relative to the
 * scene file's folder, then to the data folder ($PROXYGI_DATA_DIR, else the
 * one the build was configured with). Meshes: .off, .vtp, .obj, .stl.
 * "light_cloud" (optional) is for the light cloud (proxygi cloud): the
 * region its lights fill (xmin, xmax, ymin, ymax, zmin, zmax; default the
 * objects' bounds) and a polyline a user light moves along.
 */
#ifndef pgiScene_h
#define pgiScene_h

#include "ProxyGISceneModule.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkCamera;
class vtkPGILighting;
class vtkPolyData;
class vtkTransform;

namespace proxygi
{

struct SceneObject
{
  std::string Name;
  enum class Kind
  {
    Mesh,
    Plane,
    Sphere,
    Box
  } Type = Kind::Mesh;
  std::string MeshPath;
  double PlaneCenter[3] = { 0, 0, 0 }, PlaneSize = 1.0;
  // A quad (a plane given by its corners) instead of the square.
  bool PlaneCorners = false;
  double PlaneOrigin[3] = { 0, 0, 0 }, PlanePoint1[3] = { 1, 0, 0 }, PlanePoint2[3] = { 0, 1, 0 };
  int PlaneResolution[2] = { 64, 64 };
  double BoxCenter[3] = { 0, 0, 0 }, BoxSize[3] = { 1, 1, 1 };
  int BoxResolution = 8;
  double SphereCenter[3] = { 0, 0, 0 }, SphereRadius = 1.0;
  int SphereResolution = 64;
  double Translate[3] = { 0, 0, 0 }, Rotate[3] = { 0, 0, 0 }, Scale = 1.0;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
};

struct SceneLight
{
  bool Sphere = true;
  double Position[3] = { 0, 0, 0 };
  double Radius = 0.0;
  double Value[3] = { 1, 1, 1 }; // radiance (sphere) or intensity (point)
};

struct SceneDescription
{
  std::string Name = "scene";
  std::string BaseFolder; // where relative paths start
  std::vector<SceneObject> Objects;
  std::string EnvironmentMap; // empty: uniform
  double UniformRadiance[3] = { 1, 1, 1 };
  double EnvironmentRotation = 0.0, EnvironmentScale = 1.0;
  std::vector<SceneLight> Lights;
  double CameraPosition[3] = { 0, -4, 2 }, FocalPoint[3] = { 0, 0, 0 }, ViewUp[3] = { 0, 0, 1 };
  double ViewAngle = 30.0;
  int Size[2] = { 512, 512 };
  bool Shadows = true, Indirect = true, LocalLights = true;
  // The light cloud's region (when HasCloudRegion) and light path.
  bool HasCloudRegion = false;
  double CloudRegion[6] = { 0, 0, 0, 0, 0, 0 };
  std::vector<double> LightPath; // x, y, z per vertex
};

/// The built-in default scene: the bunny over a ground plane, forest map.
PROXYGISCENE_EXPORT SceneDescription DefaultScene();

/// An object's scale, rotation and translation, in that order.
PROXYGISCENE_EXPORT vtkSmartPointer<vtkTransform> ObjectTransform(const SceneObject& object);

/// A plane object's corners before its transform: vtkPlaneSource's origin,
/// point1 and point2 (a "plane": its square; a "quad": as given).
PROXYGISCENE_EXPORT void PlaneCorners(
  const SceneObject& object, double origin[3], double point1[3], double point2[3]);

/// A plane object as placed: its centre and half edges (the blocker
/// plane's extent, vtkPGIGlobalIllumination::AddBlockerPlane).
PROXYGISCENE_EXPORT void PlaneExtent(
  const SceneObject& object, double centre[3], double halfEdge1[3], double halfEdge2[3]);

/// Parses a JSON scene file; false with a message naming the problem.
PROXYGISCENE_EXPORT bool LoadScene(
  const std::string& path, SceneDescription& scene, std::string& error);
/// Parses JSON text (paths relative to baseFolder).
PROXYGISCENE_EXPORT bool ParseScene(const std::string& json, const std::string& baseFolder,
  SceneDescription& scene, std::string& error);

/// What the renderers consume: transformed polydata with an "Albedo" array.
struct LoadedScene
{
  std::vector<vtkSmartPointer<vtkPolyData>> Objects;
  vtkSmartPointer<vtkPGILighting> Lighting;
  vtkSmartPointer<vtkCamera> Camera;
};

/// Reads the meshes and the map, applies transforms; false with a message.
PROXYGISCENE_EXPORT bool BuildScene(
  const SceneDescription& scene, LoadedScene& loaded, std::string& error);

/// The scene's local lights as `lighting`'s (replacing the ones it had).
PROXYGISCENE_EXPORT void SetSceneLights(const SceneDescription& scene, vtkPGILighting* lighting);

/// Resolves a data path as described above ("" when not found).
PROXYGISCENE_EXPORT std::string ResolveDataPath(
  const std::string& path, const std::string& baseFolder);

} // namespace proxygi

#endif
