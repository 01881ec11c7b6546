#pragma once
// What a VTK object reports (errors and warnings), collected for our own error messages instead of
// printed to the terminal. For the files that see VTK's headers only (LabelMapSurfaces,
// volume/DicomSeries).
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>
#include <string>

namespace orthosim {

inline std::string trimmedVtkText(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

// VTK prints some errors and warnings through its output window and logger rather than to an
// object's observers: silenced once for the process; what matters reaches VtkMessages.
inline void quietVtk() {
  static std::once_flag once;
  std::call_once(once, [] {
    vtkOutputWindow::GetInstance()->SetDisplayMode(vtkOutputWindow::NEVER);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  });
}

class VtkMessages {
 public:
  explicit VtkMessages(vtkObject* source) {
    quietVtk();
    callback_->SetClientData(this);
    callback_->SetCallback([](vtkObject*, unsigned long event, void* self, void* text) {
      auto* messages = static_cast<VtkMessages*>(self);
      std::string line = text ? trimmedVtkText(static_cast<const char*>(text)) : std::string();
      // "ERROR: In .../vtkNrrdReader.cxx, line 123\nvtkNrrdReader (0x...): what": keep "what".
      const size_t colon = line.find("): ");
      if (colon != std::string::npos) line = line.substr(colon + 3);
      std::string& to = event == vtkCommand::ErrorEvent ? messages->errors : messages->warnings;
      if (!line.empty() && to.find(line) == std::string::npos) to += (to.empty() ? "" : " ") + line;
    });
    source->AddObserver(vtkCommand::ErrorEvent, callback_);
    source->AddObserver(vtkCommand::WarningEvent, callback_);
  }
  std::string errors, warnings;  // each line once, separated by spaces

 private:
  vtkSmartPointer<vtkCallbackCommand> callback_ = vtkSmartPointer<vtkCallbackCommand>::New();
};

}  // namespace orthosim
