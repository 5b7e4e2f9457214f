/*
 * image_module.hpp — what both image modules (image_oiio.cpp, image_sheet.cpp)
 * share; C++ only, the modules' own.
 */
#ifndef SL_IMAGE_MODULE_HPP
#define SL_IMAGE_MODULE_HPP
#include <string>

// Where a file is written before it is renamed into place when complete:
// the name with ".tmp" before its extension, which stays (OpenImageIO picks
// the format by it).
inline std::string sl_image_tmp_name(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return path + ".tmp";
    return path.substr(0, dot) + ".tmp" + path.substr(dot);
}

#endif
