/**
 * @class   vtkPGILightCloudPolyDataMapper
 * @brief   Relights a light cloud's receivers on the GPU (Kristensen et al.
 *          2005, section 6): the light of user point lights moving through
 *          the cloud, reconstructed per vertex, glossy receivers' SH
 *          evaluated per fragment.
 *
 * A vtkPGIGIPolyDataMapper (the GI mapper). Its input is the receivers the cloud was
 * computed for (vtkPGILightCloud::GetReceiverKey); SetCloud gives the cloud
 * (dense or compressed). The user lights, visibility rays, fade and time
 * are those of the vtkPGILightCloudRelight that GetRelight() returns: the
 * CPU filter weighs the cloud lights for both backends
 * (vtkPGILightCloudRelight::PrepareFrame), so the two cannot disagree on
 * which lights count. Per frame the mapper uploads, for a compressed cloud,
 * x_m = Xbar w_t and b_i = B_i w_t of every PCA cluster (a few hundred
 * floats); the vertex shader sums a = x_m + sum_i z_i b_i from the
 * receiver's PCA weights z (uploaded once). For a dense cloud it uploads
 * the weighted cloud lights and the vertex shader sums their responses
 * (uploaded once, as a texture buffer; a cloud larger than the GPU's
 * texture buffers is refused with an error).
 *
 * Diffuse receivers: the sum is the exit radiance, interpolated over the
 * faces. Glossy receivers (SH of order n per colour, world frame): the
 * vertex shader passes the n^2 RGB coefficients on and the fragment shader
 * evaluates them toward the camera (GlossyPerFragment, orders up to 4: 16
 * RGB coefficients, 48 interpolated floats); with GlossyPerFragment off, or
 * for higher orders, the vertex shader evaluates them toward the camera and
 * the colour is interpolated, as the CPU filter's "LightCloudRadiance" with
 * the camera as its view point.
 *
 * Direct light, two ways. With GlobalIllumination on (off by default here)
 * the GI mapper runs as it does on its own (SetLighting, proxies, settings:
 * environment light, SH soft shadows, the lighting's local lights with
 * their soft shadows) and the cloud's light is added to its radiance before
 * exposure and sRGB: the lighting's point lights are then the user lights
 * (GetRelight()'s lights are set from them each frame), direct light from
 * the soft-shadow route, indirect from the cloud. With GlobalIllumination
 * off, CombineWithVTKLighting (on by default here) adds the cloud's light to
 * VTK's lighting of the actor (e.g. the user lights as VTK positional
 * lights, unshadowed); off, the cloud's light alone (a cloud of direct and
 * indirect light).
 *
 * | property | default | meaning |
 * |---|---|---|
 * | GlobalIllumination | off | the GI mapper's own light under the cloud's |
 * | Exposure | 1 | scale of the radiance written to the image (the GI mapper's) |
 * | SRGBOutput | on | encode sRGB (the GI mapper's) |
 * | CombineWithVTKLighting | on | add to VTK's lighting (off: replace it) |
 * | GlossyPerFragment | on | glossy SH per fragment (off: per vertex) |
 *
 * GetStatus() says what the last frame ran and why: the relight filter's
 * plan lines (user lights outside the cloud are skipped with a warning,
 * no user light gives no cloud light), where the sums ran, and whether
 * the frame's light was reused (nothing changed) or recomputed.
 *
 * Errors (vtkErrorMacro, then the mesh is drawn with VTK's lighting): no
 * cloud, an empty cloud, receivers that are not the cloud's, NaN/Inf light
 * positions, a dense cloud beyond the texture buffer limit.
 */
#ifndef vtkPGILightCloudPolyDataMapper_h
#define vtkPGILightCloudPolyDataMapper_h

#include "ProxyGILightCloudRenderingModule.h"
#include "vtkNew.h"                  // for the relight filter
#include "vtkPGIGIPolyDataMapper.h"  // the base: GI under the cloud
#include "vtkPGILightCloudRelight.h" // for the relight filter

#include <memory>
#include <string>

class vtkPGILightCloud;

class PROXYGILIGHTCLOUDRENDERING_EXPORT vtkPGILightCloudPolyDataMapper
  : public vtkPGIGIPolyDataMapper
{
public:
  static vtkPGILightCloudPolyDataMapper* New();
  vtkTypeMacro(vtkPGILightCloudPolyDataMapper, vtkPGIGIPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The cloud (not owned by a pipeline: shared, kept alive by the mapper).
  virtual void SetCloud(vtkPGILightCloud* cloud);
  vtkGetObjectMacro(Cloud, vtkPGILightCloud);

  /// The user lights, visibility, fade and time (never null).
  vtkPGILightCloudRelight* GetRelight() { return this->Relight; }

  vtkSetMacro(GlossyPerFragment, bool);
  vtkGetMacro(GlossyPerFragment, bool);
  vtkBooleanMacro(GlossyPerFragment, bool);
  /// The highest glossy order evaluated per fragment (16 RGB varyings).
  static constexpr int MaxPerFragmentOrder = 4;

  /// What the last frame did with the cloud and why, one line (the GI's:
  /// GetGIStatus()).
  const std::string& GetStatus() const { return this->Status; }
  /// How many frames recomputed the cloud's light (unchanged frames reuse it).
  int GetNumberOfLightUpdates() const { return this->LightUpdates; }

  vtkMTimeType GetMTime() override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkPGILightCloudPolyDataMapper();
  ~vtkPGILightCloudPolyDataMapper() override;

  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceFinish(vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  /// Uploads what changed; false when the cloud's light cannot be drawn.
  bool UpdateCloudLight(vtkRenderer* ren);
  /// With GI on: the relight's user lights from the lighting's point lights.
  void TakeLightsFromLighting();

  vtkPGILightCloud* Cloud = nullptr;
  vtkNew<vtkPGILightCloudRelight> Relight;
  bool GlossyPerFragment = true;
  std::string Status;
  int LightUpdates = 0;

  struct Internals;
  std::unique_ptr<Internals> GPU;

private:
  vtkPGILightCloudPolyDataMapper(const vtkPGILightCloudPolyDataMapper&) = delete;
  void operator=(const vtkPGILightCloudPolyDataMapper&) = delete;
};

#endif
