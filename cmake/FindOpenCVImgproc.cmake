# FindOpenCVImgproc: OpenCV's core and imgproc libraries (Canny edges for the sonar hull line,
# SPEC §5). Debian 12's libopencv-core-dev and libopencv-imgproc-dev ship no OpenCVConfig.cmake,
# so the headers and the two libraries are found directly.
#
# Defines OpenCVImgproc_FOUND and the IMPORTED target OpenCV::imgproc (which links
# OpenCV::core). The targets are GLOBAL: the module is found in src/perception, and whatever
# links the static scantling_perception (tests, apps) needs them too. Cache hints: OpenCVImgproc_INCLUDE_DIR, OpenCVImgproc_LIBRARY,
# OpenCVCore_LIBRARY.
find_path(OpenCVImgproc_INCLUDE_DIR opencv2/imgproc.hpp PATH_SUFFIXES opencv4)
find_library(OpenCVCore_LIBRARY NAMES opencv_core)
find_library(OpenCVImgproc_LIBRARY NAMES opencv_imgproc)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenCVImgproc
  REQUIRED_VARS OpenCVImgproc_LIBRARY OpenCVCore_LIBRARY OpenCVImgproc_INCLUDE_DIR)
mark_as_advanced(OpenCVImgproc_INCLUDE_DIR OpenCVImgproc_LIBRARY OpenCVCore_LIBRARY)

if(OpenCVImgproc_FOUND AND NOT TARGET OpenCV::imgproc)
  add_library(OpenCV::core UNKNOWN IMPORTED GLOBAL)
  set_target_properties(OpenCV::core PROPERTIES
    IMPORTED_LOCATION "${OpenCVCore_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenCVImgproc_INCLUDE_DIR}")
  add_library(OpenCV::imgproc UNKNOWN IMPORTED GLOBAL)
  set_target_properties(OpenCV::imgproc PROPERTIES
    IMPORTED_LOCATION "${OpenCVImgproc_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenCVImgproc_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES OpenCV::core)
endif()
