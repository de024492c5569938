#include "report/table.h"

namespace lb {

std::string htmlEscape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char ch : s) switch (ch) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += ch;
    }
  return o;
}

// A pipe would end the Markdown cell; newlines would end the row.
static std::string mdEscape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '|')
      o += "\\|";
    else if (ch == '\n')
      o += ' ';
    else
      o += ch;
  }
  return o;
}

Cell textCell(const std::string& s) {
  return {mdEscape(s), htmlEscape(s)};
}

Cell codeCell(const std::string& s) {
  return {"`" + mdEscape(s) + "`", "<code>" + htmlEscape(s) + "</code>"};
}

Cell linkCell(const std::string& text, const std::string& mdHref, const std::string& htmlHref) {
  return {"[" + mdEscape(text) + "](" + mdHref + ")",
          "<a href=\"" + htmlEscape(htmlHref) + "\">" + htmlEscape(text) + "</a>"};
}

Cell joinCells(const std::vector<Cell>& cells, const std::string& mdSep, const std::string& htmlSep) {
  Cell out;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (i) {
      out.md += mdEscape(mdSep);
      out.html += htmlSep;
    }
    out.md += cells[i].md;
    out.html += cells[i].html;
  }
  return out;
}

static bool isNumeric(const Table& t, size_t col) {
  return col < t.numeric.size() && t.numeric[col];
}

std::string toMarkdown(const Table& t) {
  std::string s = "|";
  for (auto& h : t.header) s += " " + mdEscape(h) + " |";
  s += "\n|";
  for (size_t i = 0; i < t.header.size(); ++i) s += isNumeric(t, i) ? "---:|" : "---|";
  s += "\n";
  for (auto& row : t.rows) {
    s += "|";
    for (auto& c : row) s += " " + c.md + " |";
    s += "\n";
  }
  return s;
}

std::string toHtml(const Table& t, const std::string& cssClass) {
  std::string s = "<table class=\"" + cssClass + "\">\n<thead><tr>";
  for (size_t i = 0; i < t.header.size(); ++i) {
    const std::string h = htmlEscape(t.header[i]);
    s += i < t.headerHrefs.size() && !t.headerHrefs[i].empty()
             ? "<th><a class=\"def\" href=\"" + htmlEscape(t.headerHrefs[i]) + "\">" + h + "</a></th>"
             : "<th>" + h + "</th>";
  }
  s += "</tr></thead>\n<tbody>\n";
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    s += r < t.rowIds.size() && !t.rowIds[r].empty() ? "<tr id=\"" + htmlEscape(t.rowIds[r]) + "\">" : "<tr>";
    for (size_t i = 0; i < row.size(); ++i)
      s += std::string(isNumeric(t, i) ? "<td class=\"num\"" : "<td") + (row[i].tdAttrs.empty() ? "" : " ") +
           row[i].tdAttrs + ">" + row[i].html + "</td>";
    s += "</tr>\n";
  }
  return s + "</tbody>\n</table>\n";
}

}  // namespace lb
