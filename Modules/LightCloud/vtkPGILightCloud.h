/**
 * @class   vtkPGILightCloud
 * @brief   A light cloud (Kristensen et al. 2005): cloud lights (isotropic
 *          point lights of unit intensity at fixed positions) and, for each,
 *          the exit radiance it causes at every receiver vertex.
 *
 * vtkPGILightCloudPrecompute fills it on Embree; vtkPGILightCloudRelight
 * lights the receivers from user lights placed anywhere in the cloud. The
 * response is stored per light, receiver-major inside: RGB floats, exit
 * radiance (albedo/pi times irradiance) per unit intensity (W/sr), one
 * coefficient per colour for diffuse receivers; for glossy ones the exit
 * radiance as a function of the view direction, projected on SH of order
 * n (n^2 coefficients per colour, world frame, least squares over the
 * hemisphere above the receiver). Contents says whether it
 * holds the indirect light only (the paper's choice, since the direct light
 * compresses badly and the soft-shadow route draws it) or direct light too.
 *
 * Uncompressed: 3 x lights floats per receiver (the paper's 216 lights are
 * 648). ReceiverKey fingerprints the receivers' points so that relighting
 * refuses a mesh the cloud was not computed for. Written and read by
 * pgiLightCloudFile (vtkPGILightCloudReader reads it in a pipeline).
 */
#ifndef vtkPGILightCloud_h
#define vtkPGILightCloud_h

#include "ProxyGILightCloudModule.h"
#include "vtkDataObject.h"
#include "vtkPoints.h" // for the inline GetLightPositions
#include "vtkSmartPointer.h"

#include <cstdint>
#include <memory>
#include <vector>

class vtkPolyData;

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloud : public vtkDataObject
{
public:
  static vtkPGILightCloud* New();
  vtkTypeMacro(vtkPGILightCloud, vtkDataObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ContentsType
  {
    IndirectOnly = 0,
    DirectAndIndirect = 1
  };

  /// Sizes it for `lights` cloud lights over `receivers` receivers, with
  /// `coefficients` SH coefficients per colour (1: diffuse; n^2: glossy,
  /// order n); the positions are (0, 0, 0) and the responses 0 until set.
  void Allocate(vtkIdType lights, vtkIdType receivers, int coefficients = 1);
  vtkIdType GetNumberOfLights() const;
  vtkIdType GetNumberOfReceivers() const { return this->Receivers; }
  /// The cloud lights' positions (one point per light).
  vtkPoints* GetLightPositions() const { return this->Positions; }
  /// SH coefficients per colour: 1 (diffuse receivers) or order^2 (glossy).
  int GetCoefficients() const { return this->Coefficients; }
  /// Floats per receiver and light: 3 x GetCoefficients(), coefficient-major
  /// (coefficient 0's RGB, then coefficient 1's, ...).
  int GetValuesPerReceiver() const { return 3 * this->Coefficients; }
  /// Light j's response: GetValuesPerReceiver() x receivers floats; null
  /// once compressed.
  float* GetResponse(vtkIdType light);
  const float* GetResponse(vtkIdType light) const;

  vtkSetClampMacro(Contents, int, IndirectOnly, DirectAndIndirect);
  vtkGetMacro(Contents, int);
  /// Gather rays per receiver the precompute traced.
  vtkSetMacro(Samples, int);
  vtkGetMacro(Samples, int);
  /// Fingerprint of the receivers' points (ReceiverKeyOf).
  void SetReceiverKey(std::uint64_t key) { this->ReceiverKey = key; }
  std::uint64_t GetReceiverKey() const { return this->ReceiverKey; }
  static std::uint64_t ReceiverKeyOf(vtkPolyData* receivers);

  /**
   * The cloud's spacing: the median distance from a cloud light to its
   * nearest neighbour (0 for fewer than two lights). Relighting calls a user
   * light outside the cloud when it lies more than this beyond the lights'
   * bounding box.
   */
  double GetSpacing();
  /// The lights' bounding box (xmin, xmax, ymin, ...).
  void GetLightBounds(double bounds[6]) const;

#ifndef __VTK_WRAP__
  /**
   * The compressed form (section 5 of the paper): the receivers split into
   * zones; per zone its own cluster lights (merged from the dense cloud)
   * and, per receiver, a clustered-PCA code of its response to them: the
   * response vector x (GetValuesPerReceiver() x zone lights, light-major) is approximated as
   * Means[c] + sum_i Weights[i] Basis[c][i] for the receiver's PCA
   * cluster c.
   */
  struct Zone
  {
    std::vector<vtkIdType> Receivers; // ids into the receivers
    std::vector<double> Lights;       // cluster lights, xyz each
    std::vector<int> LightMembers;    // dense lights merged into each
    int Dimension = 0;                // values per receiver x cluster lights
    std::vector<int> Cluster;         // PCA cluster of each zone receiver
    std::vector<float> Means;         // clusters x Dimension
    std::vector<int> BasisStart;      // per PCA cluster, in vectors
    std::vector<int> BasisCount;      // vectors per PCA cluster
    std::vector<float> Basis;         // all vectors x Dimension
    std::vector<int> WeightStart;     // per zone receiver
    std::vector<float> Weights;       // BasisCount[Cluster[r]] per receiver
  };
  /// Replaces the dense responses by zones (the positions stay: they are
  /// the dense cloud's, for bounds and spacing).
  void SetZones(std::vector<Zone> zones);
  const std::vector<Zone>& GetZones() const
  {
    return *this->Zones;
  }
#endif
  /// Whether it holds zones (compressed) rather than dense responses.
  bool IsCompressed() const
  {
    return !this->Zones->empty();
  }
  vtkIdType GetNumberOfZones() const
  {
    return static_cast<vtkIdType>(this->Zones->size());
  }

  /**
   * Stored coefficients per receiver: GetValuesPerReceiver() x lights dense; compressed, the
   * mean over receivers of their PCA weights plus one (the cluster index).
   */
  double GetCoefficientsPerReceiver() const;
  /// Kibibytes held (vtkDataObject's convention).
  unsigned long GetActualMemorySize() override;

  void Initialize() override;
  void ShallowCopy(vtkDataObject* source) override;
  void DeepCopy(vtkDataObject* source) override;

  static vtkPGILightCloud* GetData(vtkInformation* info);
  static vtkPGILightCloud* GetData(vtkInformationVector* v, int i = 0);
  /// For algorithms that output a cloud: REQUEST_DATA_OBJECT's answer
  /// (a new cloud in the output information unless one is there).
  static void EnsureOutput(vtkInformationVector* out);

protected:
  vtkPGILightCloud();
  ~vtkPGILightCloud() override;

  vtkSmartPointer<vtkPoints> Positions;
  // Shared between shallow copies; light-major, then receiver, then RGB.
  std::shared_ptr<std::vector<float>> Response;
  std::shared_ptr<std::vector<Zone>> Zones;
  vtkIdType Receivers = 0;
  int Coefficients = 1;
  int Contents = IndirectOnly;
  int Samples = 0;
  std::uint64_t ReceiverKey = 0;
  double Spacing = -1.0; // cached; -1: not computed

private:
  vtkPGILightCloud(const vtkPGILightCloud&) = delete;
  void operator=(const vtkPGILightCloud&) = delete;
};

#endif
