#ifndef cbc3d_Status_h
#define cbc3d_Status_h

#include <string>
#include <utility>

namespace cbc3d
{
/// Outcome of a core function: success, or a one-line message for the user.
class Status
{
public:
  static Status Ok() { return Status(); }
  static Status Error(std::string message) { return Status(std::move(message)); }
  static Status Aborted() { return Status("aborted by the user", true); }

  bool IsOk() const { return this->Message.empty(); }
  bool WasAborted() const { return this->AbortFlag; }
  const std::string& GetMessage() const { return this->Message; }

private:
  Status() = default;
  explicit Status(std::string message, bool aborted = false)
    : Message(std::move(message))
    , AbortFlag(aborted)
  {
  }
  std::string Message;
  bool AbortFlag = false;
};
} // namespace cbc3d

#endif
