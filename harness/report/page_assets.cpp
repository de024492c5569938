#include "report/page_assets.h"

namespace lb {

namespace {

// Tables scroll inside their own box with the first column pinned, so the page itself never gets
// wider than the window (the every-case table was 1510 px at 1400).
const char* const kStyle = R"(<style>
.table-wrap { max-width: 100%; overflow-x: auto; margin: 8px 0; }
.table-wrap table { margin: 0; }
.table-wrap table.cases { display: table; }
table.sticky th:first-child, table.sticky td:first-child { position: sticky; left: 0; z-index: 1;
  background: #fff; box-shadow: 1px 0 0 #ddd; }
table.sticky thead th:first-child { background: #f3f3f3; }
table.sticky td:first-child code { white-space: nowrap; }
table th { white-space: normal; min-width: 3.5em; }
p.answer { font-size: 15px; background: #eef5ff; border-left: 4px solid #3b78c2; padding: 6px 10px; margin: 6px 0; }
p.caveat { color: #444; font-size: 13px; }
aside.howto { font-size: 12.5px; color: #333; background: #f7f7f7; border: 1px solid #e4e4e4; padding: 4px 10px;
  margin: 6px 0; }
aside.howto .howto-title { font-weight: bold; color: #3b78c2; }
aside.howto div { margin: 2px 0; }
table.grid td.num a { color: inherit; display: block; text-decoration: none; }
table.grid td.num { min-width: 4em; }
table.scenario tr:target { outline: 3px solid #f0b400; }
.shot img { width: 320px; max-width: 100%; height: auto; cursor: zoom-in; }
a.def { color: inherit; text-decoration: underline dotted #888; }
dl.glossary { display: grid; grid-template-columns: 220px 1fr; gap: 2px 12px; font-size: 13px; }
dl.glossary dt { font-weight: bold; }
dl.glossary dd { margin: 0; }
dl.glossary dt:target, dl.glossary dt:target + dd { background: #fff3c4; }
.side-grid { display: grid; gap: 6px; align-items: center; margin: 8px 0; }
.side-head { font-weight: bold; text-align: center; }
.side-label { font-size: 12px; }
.side-shot img { width: 320px; }
.flip-row { display: flex; gap: 24px; align-items: flex-start; }
.flip-row .legends { flex-direction: column; margin-top: 40px; }
.flip { margin: 8px 0 14px; }
.flip-controls { margin-bottom: 6px; font-size: 13px; }
.flip img { width: 640px; max-width: 100%; height: auto; image-rendering: pixelated; border: 1px solid #ccc; }
.legend { display: flex; align-items: center; gap: 6px; font-size: 11.5px; color: #444; margin-top: 2px; }
.legend .bar { width: 220px; height: 12px; border: 1px solid #999; }
.legend .ticks { display: flex; justify-content: space-between; width: 220px; }
.legend .swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid #999; vertical-align: middle; }
.legends { display: flex; flex-wrap: wrap; gap: 8px 28px; margin: 6px 0 12px; }
.no-image { color: #b00020; }
#zoom { position: fixed; inset: 0; background: rgba(0,0,0,0.85); display: flex; align-items: center;
  justify-content: center; z-index: 10; cursor: zoom-out; }
#zoom img { width: 96vw; height: 92vh; object-fit: contain; image-rendering: pixelated; }
span.scheme { white-space: nowrap; }
span.scheme-dot { display: inline-block; width: 10px; height: 10px; border-radius: 50%; margin-right: 4px; }
</style>
)";

// Click an image to see it as large as the window allows; click or Escape closes. The viewer's
// image exists only while open, so every <img> in the page is one of the report's.
const char* const kScript = R"(<script>
(() => {
  const close = () => { const z = document.getElementById('zoom'); if (z) z.remove(); };
  document.addEventListener('click', (e) => {
    if (document.getElementById('zoom')) { close(); return; }
    const img = e.target.closest('.shot img');
    if (!img || !img.src) return;
    const z = document.createElement('div');
    z.id = 'zoom';
    const big = document.createElement('img');
    big.src = img.src;
    big.alt = img.alt;
    z.appendChild(big);
    document.body.appendChild(z);
  });
  document.addEventListener('keydown', (e) => { if (e.key === 'Escape') close(); });
})();
// The side-by-side flip: one image showing scheme A or B in the chosen mode. Its pictures are the
// grid's own <img> elements (data-scheme, data-mode), so it works with linked and embedded images.
// This script runs at the top of the body: it waits for the elements below it.
document.addEventListener('DOMContentLoaded', () => {
  const $ = (id) => document.getElementById(id);
  const view = document.querySelector('#flip img');
  if (!view) return;
  let showB = false;
  const show = () => {
    const scheme = $(showB ? 'flip-b' : 'flip-a').value, mode = $('flip-mode').value;
    const src = [...document.querySelectorAll('.side-grid img')].find(
        (i) => i.dataset.scheme === scheme && i.dataset.mode === mode);
    if (src) { view.src = src.currentSrc || src.src; view.alt = scheme + ' ' + mode; }
    $('flip-showing').textContent = scheme + (src ? '' : ' (no ' + mode + ' image)');
  };
  const flip = () => { showB = !showB; show(); };
  $('flip-button').addEventListener('click', flip);
  ['flip-a', 'flip-b', 'flip-mode'].forEach((id) => $(id).addEventListener('change', show));
  document.addEventListener('keydown', (e) => {
    if ((e.key === 'f' || e.key === 'F') && !/^(INPUT|SELECT|TEXTAREA)$/.test(e.target.tagName)) flip();
  });
});
</script>
)";

}  // namespace

std::string pageAssetsHtml() {
  return std::string(kStyle) + kScript;
}

}  // namespace lb

#include <algorithm>

#include "report/charts.h"
#include "report/table.h"

namespace lb {

std::string pageSchemeColour(const ReportRun&, const std::string& scheme) {
  return schemeColour(scheme);  // the charts' fixed table: one colour per scheme everywhere
}

Cell schemeCell(const ReportRun& run, const std::string& scheme) {
  Cell c = textCell(scheme);
  c.html = "<span class=\"scheme\"><span class=\"scheme-dot\" style=\"background:" + pageSchemeColour(run, scheme) +
           "\"></span>" + c.html + "</span>";
  return c;
}

}  // namespace lb
