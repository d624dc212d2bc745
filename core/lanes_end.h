// Closes what core/lanes_begin.h opened.
#undef TRAY_LANE
#ifdef TRAY_LANES_SIMD
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();
#else
}  // namespace tray
#endif
