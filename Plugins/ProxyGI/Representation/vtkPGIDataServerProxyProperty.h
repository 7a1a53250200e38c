/**
 * @class   vtkPGIDataServerProxyProperty
 * @brief   A proxy property set only on processes that hold data.
 *
 * For a view's property whose value is a source (the image-space view's
 * GIProxies): with a pvserver, the source lives on the server only, and
 * ParaView's vtkSIProxyProperty aborts the client when it cannot find it
 * there. This one leaves the client's object alone (its frames are drawn on
 * the server) and sets the value everywhere else, built-in sessions included.
 * XML: si_class="vtkPGIDataServerProxyProperty".
 */
#ifndef vtkPGIDataServerProxyProperty_h
#define vtkPGIDataServerProxyProperty_h

#include "ProxyGIParaViewRepresentationModule.h"
#include "vtkSIProxyProperty.h"

class PROXYGIPARAVIEWREPRESENTATION_EXPORT vtkPGIDataServerProxyProperty : public vtkSIProxyProperty
{
public:
  static vtkPGIDataServerProxyProperty* New();
  vtkTypeMacro(vtkPGIDataServerProxyProperty, vtkSIProxyProperty);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkPGIDataServerProxyProperty() = default;
  ~vtkPGIDataServerProxyProperty() override = default;
  bool Push(vtkSMMessage* message, int offset) override;

private:
  vtkPGIDataServerProxyProperty(const vtkPGIDataServerProxyProperty&) = delete;
  void operator=(const vtkPGIDataServerProxyProperty&) = delete;
};

#endif
