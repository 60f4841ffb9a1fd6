// The one seam between the DK2 driver and whatever supplies HID reports: the real headset
// over hidapi (hid_device.h), a recording (recording.h) or a synthetic stream
// (synthetic.h). The driver cannot tell them apart (STYLE.md 11).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace photovr::hmd {

class HmdDevice {
 public:
  virtual ~HmdDevice() = default;
  // Reads one input report into 'buffer' (report ID in byte 0). Returns its length, 0 when
  // nothing arrived within timeoutMs, or -1 when the device is gone (or the stream ended).
  virtual int readReport(std::span<uint8_t> buffer, int timeoutMs) = 0;
  // Gets feature report buffer[0]; fills 'buffer' and returns the length, or -1.
  virtual int getFeature(std::span<uint8_t> buffer) = 0;
  // Sends a feature report (ID in byte 0); false when the device refused it or is gone.
  virtual bool setFeature(std::span<const uint8_t> report) = 0;
  virtual std::string name() const = 0;
};

// USB identity of the DK2 (dk2.md §1).
constexpr uint16_t kOculusVendorId = 0x2833;
constexpr uint16_t kDk2ProductId = 0x0021;

// Opens the first DK2 over hidapi; nullptr when none is attached (or it cannot be opened,
// e.g. no udev permission — 'why' then says so).
std::unique_ptr<HmdDevice> openDk2Hid(std::string* why = nullptr);

}  // namespace photovr::hmd
