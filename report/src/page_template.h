#pragma once
// The page template, made at build time (report/cmake/embed_page.cmake): report/assets/report.html
// with three.js, its orbit controls and report/assets/viewer.js inlined. Its markers <!--title-->,
// <!--content--> and <!--data--> are filled in for each page (page.cpp).
#include <string>

namespace dresskit::report::detail {

const std::string& page_template();

}  // namespace dresskit::report::detail
