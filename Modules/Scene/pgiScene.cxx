#include "pgiScene.h"

#include "vtkPGIEXRReader.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"

#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCleanPolyData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtk_jsoncpp.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace proxygi
{

vtkSmartPointer<vtkTransform> ObjectTransform(const SceneObject& object)
{
  auto transform = vtkSmartPointer<vtkTransform>::New();
  transform->PostMultiply();
  transform->Scale(object.Scale, object.Scale, object.Scale);
  transform->RotateX(object.Rotate[0]);
  transform->RotateY(object.Rotate[1]);
  transform->RotateZ(object.Rotate[2]);
  transform->Translate(object.Translate);
  return transform;
}

void PlaneCorners(const SceneObject& object, double origin[3], double point1[3], double point2[3])
{
  if (object.PlaneCorners)
  {
    std::copy_n(object.PlaneOrigin, 3, origin);
    std::copy_n(object.PlanePoint1, 3, point1);
    std::copy_n(object.PlanePoint2, 3, point2);
    return;
  }
  const double* c = object.PlaneCenter;
  const double h = 0.5 * object.PlaneSize;
  const double o[3] = { c[0] - h, c[1] - h, c[2] }, a[3] = { c[0] + h, c[1] - h, c[2] },
               b[3] = { c[0] - h, c[1] + h, c[2] };
  std::copy_n(o, 3, origin);
  std::copy_n(a, 3, point1);
  std::copy_n(b, 3, point2);
}

void PlaneExtent(
  const SceneObject& object, double centre[3], double halfEdge1[3], double halfEdge2[3])
{
  double o[3], p1[3], p2[3];
  PlaneCorners(object, o, p1, p2);
  vtkSmartPointer<vtkTransform> transform = ObjectTransform(object);
  transform->TransformPoint(o, o);
  transform->TransformPoint(p1, p1);
  transform->TransformPoint(p2, p2);
  for (int c = 0; c < 3; ++c)
  {
    halfEdge1[c] = 0.5 * (p1[c] - o[c]);
    halfEdge2[c] = 0.5 * (p2[c] - o[c]);
    centre[c] = o[c] + halfEdge1[c] + halfEdge2[c];
  }
}

SceneDescription DefaultScene()
{
  SceneDescription scene;
  scene.Name = "default: bunny over a plane, forest map";
  SceneObject bunny;
  bunny.Name = "bunny";
  bunny.MeshPath = "meshes/bunny00.off";
  // The CGAL bunny is y-up with its feet at y = -0.494; turn it z-up on z = 0.
  bunny.Rotate[0] = 90.0;
  bunny.Translate[2] = 0.494;
  bunny.Albedo[0] = bunny.Albedo[1] = bunny.Albedo[2] = 0.8;
  SceneObject ground;
  ground.Name = "ground";
  ground.Type = SceneObject::Kind::Plane;
  ground.PlaneSize = 6.0;
  ground.Albedo[0] = ground.Albedo[1] = ground.Albedo[2] = 0.5;
  scene.Objects = { bunny, ground };
  scene.EnvironmentMap = "environments/forest.exr";
  const double eye[3] = { 1.6, -2.6, 1.5 }, focal[3] = { 0, 0, 0.35 };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  scene.ViewAngle = 30.0;
  return scene;
}

namespace
{
bool ReadVector(const Json::Value& v, const char* key, double* out, int n, std::string& error)
{
  if (!v.isObject())
  {
    error = std::string("expected an object holding \"") + key + "\"";
    return false;
  }
  if (!v.isMember(key))
  {
    return true;
  }
  const Json::Value& a = v[key];
  if (!a.isArray() || static_cast<int>(a.size()) != n)
  {
    error = std::string("\"") + key + "\" must be an array of " + std::to_string(n) + " numbers";
    return false;
  }
  for (int i = 0; i < n; ++i)
  {
    if (!a[i].isNumeric() || !std::isfinite(a[i].asDouble()))
    {
      error = std::string("\"") + key + "\" holds a value that is not a finite number";
      return false;
    }
    out[i] = a[i].asDouble();
  }
  return true;
}

bool ReadNumber(const Json::Value& v, const char* key, double& out, std::string& error)
{
  if (!v.isObject())
  {
    error = std::string("expected an object holding \"") + key + "\"";
    return false;
  }
  if (!v.isMember(key))
  {
    return true;
  }
  if (!v[key].isNumeric() || !std::isfinite(v[key].asDouble()))
  {
    error = std::string("\"") + key + "\" must be a finite number";
    return false;
  }
  out = v[key].asDouble();
  return true;
}

bool ReadBool(const Json::Value& v, const char* key, bool& out, std::string& error)
{
  if (!v.isObject())
  {
    error = std::string("expected an object holding \"") + key + "\"";
    return false;
  }
  if (!v.isMember(key))
  {
    return true;
  }
  if (!v[key].isBool())
  {
    error = std::string("\"") + key + "\" must be true or false";
    return false;
  }
  out = v[key].asBool();
  return true;
}
} // namespace

namespace
{
bool ParseSceneValue(const std::string& json, const std::string& baseFolder,
  SceneDescription& scene, std::string& error);
}

bool ParseScene(const std::string& json, const std::string& baseFolder, SceneDescription& scene,
  std::string& error)
{
  // jsoncpp throws on a value of the wrong type where the checks below
  // missed one (found by fuzzing): a refusal, not a crash.
  try
  {
    return ParseSceneValue(json, baseFolder, scene, error);
  }
  catch (const std::exception& e)
  {
    error = std::string("malformed scene: ") + e.what();
    return false;
  }
}

namespace
{
bool ParseSceneValue(const std::string& json, const std::string& baseFolder,
  SceneDescription& scene, std::string& error)
{
  Json::CharReaderBuilder builder;
  std::unique_ptr<Json::CharReader> reader(builder.newCharReader());
  Json::Value root;
  std::string parseErrors;
  if (!reader->parse(json.data(), json.data() + json.size(), &root, &parseErrors))
  {
    error = "not valid JSON: " + parseErrors;
    return false;
  }
  if (!root.isObject())
  {
    error = "the scene must be a JSON object";
    return false;
  }
  scene = SceneDescription();
  scene.BaseFolder = baseFolder;
  if (root.isMember("name") && root["name"].isString())
  {
    scene.Name = root["name"].asString();
  }
  if (!root.isMember("objects") || !root["objects"].isArray() || root["objects"].empty())
  {
    error = "\"objects\" must be a non-empty array";
    return false;
  }
  for (Json::ArrayIndex i = 0; i < root["objects"].size(); ++i)
  {
    const Json::Value& o = root["objects"][i];
    const std::string where = "object " + std::to_string(i) + ": ";
    if (!o.isObject())
    {
      error = where + "must be a JSON object";
      return false;
    }
    SceneObject object;
    object.Name = o.isMember("name") && o["name"].isString() ? o["name"].asString()
                                                             : "object" + std::to_string(i);
    if (o.isMember("mesh"))
    {
      if (!o["mesh"].isString())
      {
        error = where + "\"mesh\" must be a file name";
        return false;
      }
      object.MeshPath = o["mesh"].asString();
    }
    else if (o.isMember("plane"))
    {
      object.Type = SceneObject::Kind::Plane;
      if (!ReadVector(o["plane"], "center", object.PlaneCenter, 3, error) ||
        !ReadNumber(o["plane"], "size", object.PlaneSize, error))
      {
        error.insert(0, where);
        return false;
      }
    }
    else if (o.isMember("quad"))
    {
      object.Type = SceneObject::Kind::Plane;
      object.PlaneCorners = true;
      double resolution[2] = { 32, 32 };
      if (!ReadVector(o["quad"], "origin", object.PlaneOrigin, 3, error) ||
        !ReadVector(o["quad"], "point1", object.PlanePoint1, 3, error) ||
        !ReadVector(o["quad"], "point2", object.PlanePoint2, 3, error) ||
        !ReadVector(o["quad"], "resolution", resolution, 2, error))
      {
        error.insert(0, where);
        return false;
      }
      double a[3], b[3], c[3];
      for (int k = 0; k < 3; ++k)
      {
        a[k] = object.PlanePoint1[k] - object.PlaneOrigin[k];
        b[k] = object.PlanePoint2[k] - object.PlaneOrigin[k];
      }
      c[0] = a[1] * b[2] - a[2] * b[1];
      c[1] = a[2] * b[0] - a[0] * b[2];
      c[2] = a[0] * b[1] - a[1] * b[0];
      const double area = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      const double scale = std::sqrt(
        (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
      if (!(area > 1e-9 * scale) || !(scale > 0.0))
      {
        error = where + "a quad's corners must span a parallelogram (they are collinear)";
        return false;
      }
      for (int k = 0; k < 2; ++k)
      {
        if (!(resolution[k] >= 1 && resolution[k] <= 4096))
        {
          error = where + "a quad's resolution must lie in 1..4096";
          return false;
        }
        object.PlaneResolution[k] = static_cast<int>(resolution[k]);
      }
    }
    else if (o.isMember("box"))
    {
      object.Type = SceneObject::Kind::Box;
      double resolution = object.BoxResolution;
      if (!ReadVector(o["box"], "center", object.BoxCenter, 3, error) ||
        !ReadVector(o["box"], "size", object.BoxSize, 3, error) ||
        !ReadNumber(o["box"], "resolution", resolution, error))
      {
        error.insert(0, where);
        return false;
      }
      if (!(object.BoxSize[0] > 0.0 && object.BoxSize[1] > 0.0 && object.BoxSize[2] > 0.0))
      {
        error = where + "a box's size must be positive along each axis";
        return false;
      }
      if (!(resolution >= 1 && resolution <= 1024))
      {
        error = where + "a box's resolution must lie in 1..1024";
        return false;
      }
      object.BoxResolution = static_cast<int>(resolution);
    }
    else if (o.isMember("sphere"))
    {
      object.Type = SceneObject::Kind::Sphere;
      double resolution = object.SphereResolution;
      if (!ReadVector(o["sphere"], "center", object.SphereCenter, 3, error) ||
        !ReadNumber(o["sphere"], "radius", object.SphereRadius, error) ||
        !ReadNumber(o["sphere"], "resolution", resolution, error))
      {
        error.insert(0, where);
        return false;
      }
      // Checked before the cast: a double beyond int is undefined there.
      if (!(resolution >= 3 && resolution <= 4096))
      {
        error = where + "a sphere's resolution must lie in 3..4096";
        return false;
      }
      object.SphereResolution = static_cast<int>(resolution);
    }
    else
    {
      error = where + "needs \"mesh\", \"plane\", \"quad\", \"box\" or \"sphere\"";
      return false;
    }
    if (!ReadVector(o, "translate", object.Translate, 3, error) ||
      !ReadVector(o, "rotate", object.Rotate, 3, error) ||
      !ReadNumber(o, "scale", object.Scale, error) ||
      !ReadVector(o, "albedo", object.Albedo, 3, error))
    {
      error.insert(0, where);
      return false;
    }
    for (double a : object.Albedo)
    {
      if (a < 0.0 || a > 1.0)
      {
        error = where + "albedo must lie in [0, 1]";
        return false;
      }
    }
    if (!(object.Scale > 0.0) || !(object.PlaneSize > 0.0) || !(object.SphereRadius > 0.0) ||
      object.SphereResolution < 3)
    {
      error = where + "scale, size and radius must be positive, resolution at least 3";
      return false;
    }
    scene.Objects.push_back(object);
  }
  if (root.isMember("environment"))
  {
    const Json::Value& e = root["environment"];
    if (!e.isObject())
    {
      error = "\"environment\" must be a JSON object";
      return false;
    }
    if (e.isMember("map"))
    {
      if (!e["map"].isString())
      {
        error = "environment: \"map\" must be a file name";
        return false;
      }
      scene.EnvironmentMap = e["map"].asString();
    }
    if (!ReadVector(e, "uniform", scene.UniformRadiance, 3, error) ||
      !ReadNumber(e, "rotation", scene.EnvironmentRotation, error) ||
      !ReadNumber(e, "scale", scene.EnvironmentScale, error))
    {
      error = "environment: " + error;
      return false;
    }
  }
  if (root.isMember("lights"))
  {
    if (!root["lights"].isArray())
    {
      error = "\"lights\" must be an array";
      return false;
    }
    for (const Json::Value& l : root["lights"])
    {
      SceneLight light;
      const std::string type =
        l.isObject() && l["type"].isString() ? l["type"].asString() : std::string();
      if (type == "sphere")
      {
        light.Sphere = true;
        if (!ReadVector(l, "center", light.Position, 3, error) ||
          !ReadNumber(l, "radius", light.Radius, error) ||
          !ReadVector(l, "radiance", light.Value, 3, error))
        {
          error.insert(0, "sphere light: ");
          return false;
        }
      }
      else if (type == "point")
      {
        light.Sphere = false;
        if (!ReadVector(l, "position", light.Position, 3, error) ||
          !ReadVector(l, "intensity", light.Value, 3, error))
        {
          error.insert(0, "point light: ");
          return false;
        }
      }
      else
      {
        error = "a light's \"type\" must be \"sphere\" or \"point\"";
        return false;
      }
      if (light.Radius < 0.0 || light.Value[0] < 0.0 || light.Value[1] < 0.0 ||
        light.Value[2] < 0.0)
      {
        error = "a light's radius, radiance and intensity must not be negative";
        return false;
      }
      scene.Lights.push_back(light);
    }
  }
  if (root.isMember("camera"))
  {
    const Json::Value& c = root["camera"];
    double size[2] = { double(scene.Size[0]), double(scene.Size[1]) };
    if (!ReadVector(c, "position", scene.CameraPosition, 3, error) ||
      !ReadVector(c, "focal_point", scene.FocalPoint, 3, error) ||
      !ReadVector(c, "view_up", scene.ViewUp, 3, error) ||
      !ReadNumber(c, "view_angle", scene.ViewAngle, error) ||
      !ReadVector(c, "size", size, 2, error))
    {
      error = "camera: " + error;
      return false;
    }
    if (!(size[0] >= 1 && size[1] >= 1 && size[0] <= 16384 && size[1] <= 16384))
    {
      error = "camera: size must lie in 1..16384";
      return false;
    }
    scene.Size[0] = static_cast<int>(size[0]);
    scene.Size[1] = static_cast<int>(size[1]);
  }
  if (root.isMember("effects"))
  {
    const Json::Value& e = root["effects"];
    if (!ReadBool(e, "shadows", scene.Shadows, error) ||
      !ReadBool(e, "indirect", scene.Indirect, error) ||
      !ReadBool(e, "local_lights", scene.LocalLights, error))
    {
      error = "effects: " + error;
      return false;
    }
  }
  if (root.isMember("light_cloud"))
  {
    const Json::Value& c = root["light_cloud"];
    if (!c.isObject())
    {
      error = "light_cloud must be an object";
      return false;
    }
    if (c.isMember("region"))
    {
      if (!ReadVector(c, "region", scene.CloudRegion, 6, error))
      {
        error = "light_cloud: " + error;
        return false;
      }
      for (int a = 0; a < 3; ++a)
      {
        if (!(scene.CloudRegion[2 * a] <= scene.CloudRegion[2 * a + 1]))
        {
          error = "light_cloud: region must be xmin, xmax, ymin, ymax, zmin, zmax";
          return false;
        }
      }
      scene.HasCloudRegion = true;
    }
    if (c.isMember("path"))
    {
      const Json::Value& path = c["path"];
      if (!path.isArray() || path.size() < 2 || path.size() > 4096)
      {
        error = "light_cloud: path must be an array of 2 to 4096 points";
        return false;
      }
      for (const Json::Value& point : path)
      {
        Json::Value holder(Json::objectValue);
        holder["p"] = point;
        double p[3];
        if (!ReadVector(holder, "p", p, 3, error))
        {
          error = "light_cloud: each path point must be an array of 3 finite numbers";
          return false;
        }
        scene.LightPath.insert(scene.LightPath.end(), p, p + 3);
      }
    }
  }
  return true;
}
} // namespace

bool LoadScene(const std::string& path, SceneDescription& scene, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open scene file '" + path + "'";
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash);
  if (!ParseScene(text.str(), folder, scene, error))
  {
    error = path + ": " + error;
    return false;
  }
  return true;
}

std::string ResolveDataPath(const std::string& path, const std::string& baseFolder)
{
  auto exists = [](const std::string& p) { return static_cast<bool>(std::ifstream(p)); };
  if (!path.empty() && path[0] == '/')
  {
    return exists(path) ? path : std::string();
  }
  if (!baseFolder.empty() && exists(baseFolder + "/" + path))
  {
    return baseFolder + "/" + path;
  }
  const char* env = std::getenv("PROXYGI_DATA_DIR");
  const std::string data = env && *env ? env : PROXYGI_DEFAULT_DATA_DIR;
  return exists(data + "/" + path) ? data + "/" + path : std::string();
}

namespace
{
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error)
{
  const std::size_t dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(c));
  }
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == "off")
  {
    auto r = vtkSmartPointer<vtkPGIOFFReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    error = "unknown mesh format '" + ext + "' (use .off, .obj, .stl or .vtp)";
    return nullptr;
  }
  reader->Update();
  vtkPolyData* mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!mesh || mesh->GetNumberOfPolys() == 0)
  {
    error = "'" + path + "' holds no polygons";
    return nullptr;
  }
  return mesh;
}
} // namespace

void SetSceneLights(const SceneDescription& scene, vtkPGILighting* lighting)
{
  lighting->RemoveAllLights();
  for (const SceneLight& l : scene.Lights)
  {
    if (l.Sphere)
    {
      lighting->AddSphereLight(l.Position, l.Radius, l.Value);
    }
    else
    {
      lighting->AddPointLight(l.Position, l.Value);
    }
  }
}

namespace
{
// Six faces, each its own points (sharp edges keep their normals), outward.
vtkSmartPointer<vtkPolyData> BoxMesh(const double c[3], const double size[3], int resolution)
{
  vtkNew<vtkAppendPolyData> faces;
  for (int axis = 0; axis < 3; ++axis)
  {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = -1; side <= 1; side += 2)
    {
      double origin[3], p1[3], p2[3];
      for (int k = 0; k < 3; ++k)
      {
        origin[k] = p1[k] = p2[k] = c[k] - 0.5 * size[k];
      }
      origin[axis] = p1[axis] = p2[axis] = c[axis] + 0.5 * side * size[axis];
      // (p1 - origin) x (p2 - origin) points along +axis; swap for -axis.
      p1[u] += size[u];
      p2[v] += size[v];
      vtkNew<vtkPlaneSource> face;
      face->SetOrigin(origin);
      face->SetPoint1(side > 0 ? p1 : p2);
      face->SetPoint2(side > 0 ? p2 : p1);
      face->SetResolution(resolution, resolution);
      face->Update();
      faces->AddInputData(face->GetOutput());
    }
  }
  faces->Update();
  vtkSmartPointer<vtkPolyData> mesh = faces->GetOutput();
  return mesh;
}
} // namespace

bool BuildScene(const SceneDescription& scene, LoadedScene& loaded, std::string& error)
{
  loaded = LoadedScene();
  for (const SceneObject& object : scene.Objects)
  {
    vtkSmartPointer<vtkPolyData> mesh;
    if (object.Type == SceneObject::Kind::Mesh)
    {
      const std::string path = ResolveDataPath(object.MeshPath, scene.BaseFolder);
      if (path.empty())
      {
        error = object.Name + ": mesh '" + object.MeshPath +
          "' not found (run Utilities/setup.sh --data, or set PROXYGI_DATA_DIR)";
        return false;
      }
      mesh = ReadMesh(path, error);
      if (!mesh)
      {
        error.insert(0, ": ").insert(0, object.Name);
        return false;
      }
    }
    else if (object.Type == SceneObject::Kind::Plane)
    {
      vtkNew<vtkPlaneSource> plane;
      double o[3], p1[3], p2[3];
      PlaneCorners(object, o, p1, p2);
      plane->SetOrigin(o);
      plane->SetPoint1(p1);
      plane->SetPoint2(p2);
      if (object.PlaneCorners)
      {
        plane->SetResolution(object.PlaneResolution[0], object.PlaneResolution[1]);
      }
      else
      {
        plane->SetResolution(64, 64);
      }
      plane->Update();
      mesh = plane->GetOutput();
    }
    else if (object.Type == SceneObject::Kind::Box)
    {
      mesh = BoxMesh(object.BoxCenter, object.BoxSize, object.BoxResolution);
    }
    else
    {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetCenter(object.SphereCenter[0], object.SphereCenter[1], object.SphereCenter[2]);
      sphere->SetRadius(object.SphereRadius);
      sphere->SetThetaResolution(object.SphereResolution);
      sphere->SetPhiResolution(object.SphereResolution / 2 + 1);
      sphere->Update();
      mesh = sphere->GetOutput();
    }
    vtkNew<vtkTransformPolyDataFilter> moved;
    moved->SetInputData(mesh);
    moved->SetTransform(ObjectTransform(object));
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(moved->GetOutputPort());
    triangles->PassVertsOff();
    triangles->PassLinesOff();
    triangles->Update();
    auto result = vtkSmartPointer<vtkPolyData>::New();
    result->DeepCopy(triangles->GetOutput());
    vtkNew<vtkFloatArray> albedo;
    albedo->SetName("Albedo");
    albedo->SetNumberOfComponents(3);
    albedo->SetNumberOfTuples(result->GetNumberOfPoints());
    const float a[3] = { float(object.Albedo[0]), float(object.Albedo[1]),
      float(object.Albedo[2]) };
    for (vtkIdType i = 0; i < result->GetNumberOfPoints(); ++i)
    {
      albedo->SetTypedTuple(i, a);
    }
    result->GetPointData()->AddArray(albedo);
    loaded.Objects.push_back(result);
  }

  loaded.Lighting = vtkSmartPointer<vtkPGILighting>::New();
  if (!scene.EnvironmentMap.empty())
  {
    const std::string path = ResolveDataPath(scene.EnvironmentMap, scene.BaseFolder);
    if (path.empty())
    {
      error = "environment map '" + scene.EnvironmentMap +
        "' not found (run Utilities/setup.sh --data, or set PROXYGI_DATA_DIR)";
      return false;
    }
    vtkNew<vtkPGIEXRReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    if (reader->GetOutput()->GetNumberOfPoints() == 0)
    {
      error = "cannot read environment map '" + path + "'";
      return false;
    }
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(reader->GetOutput());
    if (scene.EnvironmentScale != 1.0)
    {
      vtkDataArray* s = image->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < s->GetNumberOfValues(); ++i)
      {
        s->SetVariantValue(i, s->GetVariantValue(i).ToDouble() * scene.EnvironmentScale);
      }
    }
    loaded.Lighting->SetEnvironmentImage(image);
  }
  else
  {
    double u[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = scene.UniformRadiance[k] * scene.EnvironmentScale;
    }
    loaded.Lighting->SetUniformRadiance(u);
  }
  loaded.Lighting->SetEnvironmentRotation(scene.EnvironmentRotation);
  SetSceneLights(scene, loaded.Lighting);
  loaded.Camera = vtkSmartPointer<vtkCamera>::New();
  loaded.Camera->SetPosition(scene.CameraPosition);
  loaded.Camera->SetFocalPoint(scene.FocalPoint);
  loaded.Camera->SetViewUp(scene.ViewUp);
  loaded.Camera->SetViewAngle(scene.ViewAngle);
  return true;
}

} // namespace proxygi
