#pragma once
// One table, written both as Markdown (report.md) and as HTML (report.html). A cell holds its two
// renderings because links differ: Markdown links point at files, HTML links at in-page anchors.
#include <string>
#include <vector>

namespace lb {

struct Cell {
  std::string md, html;
  std::string tdAttrs;  // raw attributes of the HTML cell (e.g. a background), "" for none
};

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<Cell>> rows;
  std::vector<bool> numeric;             // right-aligned columns (optional, per header entry)
  std::vector<std::string> rowIds;       // HTML id of each row (optional): link targets
  std::vector<std::string> headerHrefs;  // HTML link of each header (optional): its definition
};

std::string htmlEscape(const std::string& s);
Cell textCell(const std::string& s);
Cell codeCell(const std::string& s);
// A link whose Markdown target is a file path and whose HTML target is an anchor ("#...").
Cell linkCell(const std::string& text, const std::string& mdHref, const std::string& htmlHref);
// Joins cells (e.g. several links in one cell); htmlSep is raw HTML such as "<br>".
Cell joinCells(const std::vector<Cell>& cells, const std::string& mdSep, const std::string& htmlSep);

std::string toMarkdown(const Table& t);
std::string toHtml(const Table& t, const std::string& cssClass);

}  // namespace lb
