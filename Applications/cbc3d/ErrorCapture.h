#ifndef cbc3d_ErrorCapture_h
#define cbc3d_ErrorCapture_h

#include <vtkCommand.h>
#include <vtkObject.h>

#include <string>

/// Catches vtkErrorMacro / vtkWarningMacro output of the objects it observes, so the command
/// prints one clean line instead of VTK's multi-line report.
class ErrorCapture : public vtkCommand
{
public:
  static ErrorCapture* New() { return new ErrorCapture; }

  void Observe(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string text = Clean(callData ? static_cast<const char*>(callData) : "");
    if (event == vtkCommand::ErrorEvent && this->Error.empty())
    {
      this->Error = text;
    }
    else if (event == vtkCommand::WarningEvent)
    {
      this->Warnings += (this->Warnings.empty() ? "" : "\n") + text;
    }
  }

  std::string Error;
  std::string Warnings;

private:
  // VTK formats "ERROR: In FILE, line N\nClass (0xADDR): message\n\n": keep the message.
  static std::string Clean(std::string text)
  {
    const std::size_t marker = text.find("): ");
    if (marker != std::string::npos)
    {
      text = text.substr(marker + 3);
    }
    for (char& c : text)
    {
      c = (c == '\n' || c == '\r') ? ' ' : c;
    }
    const std::size_t last = text.find_last_not_of(' ');
    return last == std::string::npos ? std::string() : text.substr(0, last + 1);
  }
};

#endif
