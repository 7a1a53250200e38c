/**
 * @class   vtkPGIReferenceImage
 * @brief   Ground-truth image of a diffuse scene seen by a vtkCamera, path
 *          traced on Embree (one primary ray through each pixel centre,
 *          Samples irradiance samples at its hit).
 *
 * Input 0 (repeatable): the scene objects (vtkPolyData). Input 1 (optional):
 * sphere proxies, which replace the objects when UseProxies is on. Light: a
 * vtkPGILighting; pixels that see no geometry show the environment.
 * Output: vtkImageData Width x Height, RGB float point arrays "Radiance"
 * (the scalars), "DirectShadowed", "IndirectOneBounce" and "RadianceStdErr";
 * VTK row order (row 0 at the bottom).
 * Write it with vtkPGIEXRWriter, or tone-map it for a PNG.
 */
#ifndef vtkPGIReferenceImage_h
#define vtkPGIReferenceImage_h

#include "ProxyGIReferenceModule.h"
#include "vtkImageAlgorithm.h"

class vtkCamera;
class vtkPGILighting;

class PROXYGIREFERENCE_EXPORT vtkPGIReferenceImage : public vtkImageAlgorithm
{
public:
  static vtkPGIReferenceImage* New();
  vtkTypeMacro(vtkPGIReferenceImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);
  virtual void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);

  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  vtkSetClampMacro(Samples, int, 1, 1 << 24);
  vtkGetMacro(Samples, int);
  vtkSetClampMacro(MaxBounces, int, 0, 64);
  vtkGetMacro(MaxBounces, int);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  vtkSetMacro(UseProxies, bool);
  vtkGetMacro(UseProxies, bool);
  vtkBooleanMacro(UseProxies, bool);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);

  vtkMTimeType GetMTime() override;

protected:
  vtkPGIReferenceImage();
  ~vtkPGIReferenceImage() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPGILighting* Lighting = nullptr;
  vtkCamera* Camera = nullptr;
  int Size[2] = { 256, 256 };
  int Samples = 64;
  int MaxBounces = 1;
  unsigned int Seed = 1;
  bool UseProxies = false;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;

private:
  vtkPGIReferenceImage(const vtkPGIReferenceImage&) = delete;
  void operator=(const vtkPGIReferenceImage&) = delete;
};

#endif
