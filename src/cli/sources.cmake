# The shadowlab executable: main.cpp declares the subcommands; each command's work is in its own file.
set(SL_CLI_SOURCES
  src/cli/main.cpp
  src/cli/Commands.cpp
  src/cli/RenderCommand.cpp
  src/cli/ListCommand.cpp
  src/cli/ReferenceCommand.cpp
  src/cli/CompareCommand.cpp
  src/cli/BenchCommand.cpp
  src/cli/BenchRunCommand.cpp
  src/cli/ProbeCommand.cpp
  src/cli/MontageCommand.cpp
  src/cli/LessonsCommand.cpp
  src/cli/ViewCommand.cpp
  src/cli/ViewerSession.cpp
  src/cli/ViewerWindow.cpp
  src/cli/vtkSLViewerInteractorStyle.cxx
  src/cli/XDisplay.cpp)
