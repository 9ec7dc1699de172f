#pragma once
// report.html of a dressing run (outputs.cpp): the body and garments in 3D, placed and dressed,
// coloured by part, by distance to the body and by strain, and the report's figures as tables and
// plots.
#include <string>

#include "dresskit/dressing/dress.h"
#include "dresskit/report/page.h"

namespace dresskit::dressing::detail {

/// The page of a dressing run without its report.json text (set page.report_json once it is made).
/// `command` names the command ("dress", "demo"); `failure` is "" for a run that succeeded, else
/// what failed (the garments are then shown at the last good state settling reached).
report::ReportPage dress_page(const DressResult& result, const std::string& command,
                      const std::string& failure);

}  // namespace dresskit::dressing::detail
