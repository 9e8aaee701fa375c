#include "vis/vtkSLPointLabels.h"

#include <vtkContext2D.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>

#include <algorithm>

vtkStandardNewMacro(vtkSLPointLabels);

vtkSLPointLabels::vtkSLPointLabels()
  : TextProperties(vtkSmartPointer<vtkTextProperty>::New())
{
  this->TextProperties->SetFontSize(12);
  this->TextProperties->SetColor(0.15, 0.15, 0.15);
  this->TextProperties->SetJustificationToLeft();
  this->TextProperties->SetVerticalJustificationToBottom();
  // An empty label list: the legend lists the plots' labels, and these strings are no series.
  vtkNew<vtkStringArray> noLegendEntries;
  this->vtkPlot::SetLabels(noLegendEntries);
}

void vtkSLPointLabels::SetLabels(
  const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::string>& texts)
{
  this->X = x;
  this->Y = y;
  this->Texts = texts;
  this->Texts.resize(std::min({ x.size(), y.size(), texts.size() }));
  this->Modified();
}

bool vtkSLPointLabels::Paint(vtkContext2D* painter)
{
  if (!this->Visible)
  {
    return false;
  }
  painter->ApplyTextProp(this->TextProperties);
  for (std::size_t i = 0; i < this->Texts.size(); ++i)
  {
    // Two spaces keep the text clear of the point's marker.
    painter->DrawString(static_cast<float>(this->X[i]), static_cast<float>(this->Y[i]), "  " + this->Texts[i]);
  }
  return true;
}

bool vtkSLPointLabels::PaintLegend(vtkContext2D*, const vtkRectf&, int)
{
  return false;
}

void vtkSLPointLabels::GetBounds(double bounds[4])
{
  if (this->Texts.empty())
  {
    bounds[0] = bounds[2] = 0.0;
    bounds[1] = bounds[3] = 1.0;
    return;
  }
  bounds[0] = *std::min_element(this->X.begin(), this->X.begin() + this->Texts.size());
  bounds[1] = *std::max_element(this->X.begin(), this->X.begin() + this->Texts.size());
  bounds[2] = *std::min_element(this->Y.begin(), this->Y.begin() + this->Texts.size());
  bounds[3] = *std::max_element(this->Y.begin(), this->Y.begin() + this->Texts.size());
}

void vtkSLPointLabels::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Labels: " << this->Texts.size() << "\n";
  for (std::size_t i = 0; i < this->Texts.size(); ++i)
  {
    os << indent.GetNextIndent() << "(" << this->X[i] << ", " << this->Y[i] << ") " << this->Texts[i] << "\n";
  }
}
