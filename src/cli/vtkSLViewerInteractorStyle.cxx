#include "cli/vtkSLViewerInteractorStyle.h"

#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

vtkStandardNewMacro(vtkSLViewerInteractorStyle);

void vtkSLViewerInteractorStyle::OnChar()
{
  vtkRenderWindowInteractor* interactor = this->GetInteractor();
  if (interactor && this->OnKey)
  {
    const char* keySym = interactor->GetKeySym();
    this->OnKey(interactor->GetKeyCode(), keySym ? keySym : "");
  }
}

void vtkSLViewerInteractorStyle::OnLeftButtonDown()
{
  vtkRenderWindowInteractor* interactor = this->GetInteractor();
  if (interactor && this->OnClick)
  {
    const int* position = interactor->GetEventPosition();
    this->OnClick(position[0], position[1]);
  }
}

void vtkSLViewerInteractorStyle::OnConfigure()
{
  if (this->OnResize)
  {
    this->OnResize();
  }
}

void vtkSLViewerInteractorStyle::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KeyHandler: " << (this->OnKey ? "set" : "none") << "\n";
  os << indent << "ClickHandler: " << (this->OnClick ? "set" : "none") << "\n";
  os << indent << "ResizeHandler: " << (this->OnResize ? "set" : "none") << "\n";
}
