// The summed-area table's build (structures/sat/SatStructure.h; savsm, vssm): the summed-area table of the
// shadow map's (z, z^2), two compute passes per band of rows (structures/sat/shaders/SatBuild.glsl,
// gl/BandedPrefixSums.h). Parameter read: sat_precision (float_centred | int32).
#pragma once

#include "gl/BandedPrefixSums.h"
#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <map>
#include <memory>

class vtkSLSatPass : public vtkSLStagePass
{
public:
  static vtkSLSatPass* New();
  vtkTypeMacro(vtkSLSatPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "summed_area_table"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLSatPass();
  ~vtkSLSatPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLSatPass(const vtkSLSatPass&) = delete;
  void operator=(const vtkSLSatPass&) = delete;

  // Compiled programs by (integer?, pass).
  std::map<std::pair<bool, int>, std::unique_ptr<sl::ComputeProgram>> Programs;
  // The last table built, reused by the next frame when its size and format fit.
  vtkSmartPointer<vtkTextureObject> Table;
  unsigned TableInternalFormat = 0;
  // The band and carry buffers the table is built in (gl/BandedPrefixSums.h), kept with the table.
  sl::BandedPrefixSums Bands;
};
