#pragma once
// The torch-free runtime's file (docs/runtime.md): its name in a model directory and the format
// tag it carries. Written by learn/runtime_export, read by control/ (which must not see LibTorch).
namespace mimic {

inline constexpr const char* kRuntimeFileName = "networks.mimic";
inline constexpr const char* kRuntimeFormat = "mimic skill networks";

}  // namespace mimic
