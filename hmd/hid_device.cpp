// The real DK2 over hidapi: the only file that calls it (STYLE.md 2).
#include <mutex>

#include <hidapi.h>

#include "hmd/hmd_device.h"

namespace photovr::hmd {
namespace {

std::string narrow(const wchar_t* w) {
  std::string s;
  for (; w && *w; ++w) s += *w < 128 ? char(*w) : '?';
  return s;
}

// hid_init/hid_exit are process-wide; keep the library initialised while a device is open.
std::mutex gInitMutex;
int gOpenDevices = 0;

class HidapiDevice final : public HmdDevice {
 public:
  explicit HidapiDevice(hid_device* d) : device_(d) {}
  ~HidapiDevice() override {
    hid_close(device_);
    std::lock_guard lock(gInitMutex);
    if (--gOpenDevices == 0) hid_exit();
  }
  int readReport(std::span<uint8_t> buffer, int timeoutMs) override {
    return hid_read_timeout(device_, buffer.data(), buffer.size(), timeoutMs);
  }
  int getFeature(std::span<uint8_t> buffer) override {
    return hid_get_feature_report(device_, buffer.data(), buffer.size());
  }
  bool setFeature(std::span<const uint8_t> report) override {
    return hid_send_feature_report(device_, report.data(), report.size()) == int(report.size());
  }
  std::string name() const override { return "DK2 (hidapi)"; }

 private:
  hid_device* device_;
};

}  // namespace

std::unique_ptr<HmdDevice> openDk2Hid(std::string* why) {
  std::lock_guard lock(gInitMutex);
  if (gOpenDevices == 0 && hid_init() != 0) {
    if (why) *why = "hidapi: " + narrow(hid_error(nullptr));
    return nullptr;
  }
  hid_device* d = hid_open(kOculusVendorId, kDk2ProductId, nullptr);
  if (!d) {
    if (why) *why = "no Rift DK2 (USB 2833:0021) found or no permission to open it";
    if (gOpenDevices == 0) hid_exit();
    return nullptr;
  }
  ++gOpenDevices;
  return std::make_unique<HidapiDevice>(d);
}

}  // namespace photovr::hmd
