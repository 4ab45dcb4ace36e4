// oidn_api.h: the few Open Image Denoise 2.x C API entry points montecl calls, declared here as
// function-pointer types (the library is dlopened, its headers are not installed: PyPI's pyoidn
// wheel ships only the shared libraries). Values and signatures follow OIDN 2.x's public API
// (include/OpenImageDenoise/oidn.h); checked against the exported symbols of OIDN 2.5.1.
// Reads and writes nothing.
#pragma once
#include <cstddef>

namespace montecl::oidn {

// Opaque handles (pointers to the library's own objects).
using Device = struct DeviceImpl*;
using Filter = struct FilterImpl*;

// OIDNDeviceType
constexpr int kDeviceTypeCpu = 1;
// OIDNError
constexpr int kErrorNone = 0;
// OIDNFormat: 32-bit float, three channels per pixel.
constexpr int kFormatFloat3 = 3;
// OIDNQuality: 0 is the library's default, which is high.
constexpr int kQualityFast = 4, kQualityBalanced = 5, kQualityHigh = 6;

extern "C" {
using NewDeviceFn = Device (*)(int type);
using CommitDeviceFn = void (*)(Device);
using ReleaseDeviceFn = void (*)(Device);
using GetDeviceErrorFn = int (*)(Device, const char** message);
using NewFilterFn = Filter (*)(Device, const char* type);
using SetSharedFilterImageFn = void (*)(Filter, const char* name, void* ptr, int format, std::size_t width,
                                        std::size_t height, std::size_t byteOffset, std::size_t bytePixelStride,
                                        std::size_t byteRowStride);
using SetFilterBoolFn = void (*)(Filter, const char* name, bool value);
using SetFilterIntFn = void (*)(Filter, const char* name, int value);
using CommitFilterFn = void (*)(Filter);
using ExecuteFilterFn = void (*)(Filter);
using ReleaseFilterFn = void (*)(Filter);
}

// The symbols, as the library exports them (2.x names: oidnSetFilterBool, not 1.x's oidnSetFilter1b).
struct Api {
  NewDeviceFn newDevice = nullptr;                    // oidnNewDevice
  CommitDeviceFn commitDevice = nullptr;              // oidnCommitDevice
  ReleaseDeviceFn releaseDevice = nullptr;            // oidnReleaseDevice
  GetDeviceErrorFn getDeviceError = nullptr;          // oidnGetDeviceError
  NewFilterFn newFilter = nullptr;                    // oidnNewFilter
  SetSharedFilterImageFn setSharedFilterImage = nullptr;  // oidnSetSharedFilterImage
  SetFilterBoolFn setFilterBool = nullptr;            // oidnSetFilterBool
  SetFilterIntFn setFilterInt = nullptr;              // oidnSetFilterInt
  CommitFilterFn commitFilter = nullptr;              // oidnCommitFilter
  ExecuteFilterFn executeFilter = nullptr;            // oidnExecuteFilter
  ReleaseFilterFn releaseFilter = nullptr;            // oidnReleaseFilter
};

}  // namespace montecl::oidn
