// Text beside data points of a vtkChartXY: a plot whose only marks are strings, each drawn just right of and above
// its (x, y) in the chart's data coordinates, at a fixed pixel size however the axes scale (vtkContext2D places
// strings through the transform but draws them unscaled). The bench's speed-against-error chart labels each point
// of a sweep with its swept value with it. It adds no legend entry.
#pragma once

#include <vtkPlot.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkTextProperty;

class vtkSLPointLabels : public vtkPlot
{
public:
  static vtkSLPointLabels* New();
  vtkTypeMacro(vtkSLPointLabels, vtkPlot);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Replaces every label; x and y in the chart's data units (the values the other plots' tables hold).
  void SetLabels(const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::string>& texts);
  vtkTextProperty* GetTextProperties() { return this->TextProperties; }

  bool Paint(vtkContext2D* painter) override;
  bool PaintLegend(vtkContext2D* painter, const vtkRectf& rect, int legendIndex) override;
  void GetBounds(double bounds[4]) override;

protected:
  vtkSLPointLabels();
  ~vtkSLPointLabels() override = default;

private:
  vtkSLPointLabels(const vtkSLPointLabels&) = delete;
  void operator=(const vtkSLPointLabels&) = delete;

  std::vector<double> X;
  std::vector<double> Y;
  std::vector<std::string> Texts;
  vtkSmartPointer<vtkTextProperty> TextProperties;
};
