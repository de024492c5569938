#pragma once
// What body.html brings of its own on top of report/render.mjs's page: the page's layout rules
// (tables that fit 1400 px, image sizes), the click-to-enlarge viewer and the side-by-side flip,
// inline (no network).
#include <string>

namespace lb {

// A <style> element and a <script> element, written at the top of body.html.
std::string pageAssetsHtml();

}  // namespace lb

namespace lb {

struct ReportRun;
// The colour the page gives a scheme's name (a dot before it in tables), the same as the charts'.
// The one place to redirect when charts.h's fixed scheme colour table lands (charts helper).
std::string pageSchemeColour(const ReportRun& run, const std::string& scheme);
// textCell(scheme) with the scheme's colour dot in HTML.
struct Cell;
Cell schemeCell(const ReportRun& run, const std::string& scheme);

}  // namespace lb
