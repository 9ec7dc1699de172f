#pragma once
// The static HTML of a report page (page.cpp): text escaped for HTML, and each section below the 3D
// view as a table or an inline SVG plot, readable without script or WebGL.
#include <string>

#include "dresskit/report/page.h"

namespace dresskit::report::detail {

/// Text with &, <, >, " and ' escaped for HTML text and attribute values.
std::string escape_html(const std::string& text);

/// One section as HTML: <section><h2>…</h2> and its table, SVG or paragraph.
std::string section_html(const ReportSection& section);

}  // namespace dresskit::report::detail
