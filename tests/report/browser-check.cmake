# Loads an HTML page in headless Chromium (a real render: layout, scripts, image decoding) and
# checks from the rendered DOM that
#   - every <img> decoded (complete, naturalWidth > 0): no broken image;
#   - each selector in EXPECT matches exactly the expected number of elements ("SEL=N"; a selector
#     starting with "points " counts the points of the matching SVG polylines instead);
#   - a flip toggle, where the page has one (#flip-toggle), flips #flip-view from the reference
#     (#golden-reference) to the test frame (#frame) and back (data-showing names which it shows);
#   - for each selector in NO_OVERLAP, no two of its elements overlap on the rendered page (their
#     bounding boxes, e.g. a chart's point labels); it must match at least two elements;
#   - for each "SEL=REGEX" in FORBID_TEXT (split at the first '='), no element matching SEL has text
#     matching REGEX (a JavaScript regular expression, e.g. an axis tick printed as 2.38e+03); SEL
#     must match at least one element.
# It also saves a screenshot, PAGE.png, for a person to look at. A probe script is added to a copy of
# the page (PAGE.probe.html, same folder, so relative links behave the same); the page itself is
# not changed.
# Inputs (-D): CHROMIUM, PAGE, EXPECT (";"-separated SEL=N) or EXPECT_FILE (one SEL=N per line),
# MIN_IMAGES (default 1), NO_OVERLAP (";"-separated selectors), FORBID_TEXT (";"-separated SEL=REGEX).
foreach(var CHROMIUM PAGE)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "" OR "${${var}}" MATCHES "NOTFOUND$")
    message(FATAL_ERROR "browser-check: ${var} is missing (${${var}}); scripts/setup.sh --tests installs chromium")
  endif()
endforeach()
if(NOT EXISTS "${PAGE}")
  message(FATAL_ERROR "browser-check: ${PAGE} does not exist")
endif()
if(DEFINED EXPECT_FILE)
  file(STRINGS "${EXPECT_FILE}" EXPECT)
endif()
if(NOT DEFINED MIN_IMAGES)
  set(MIN_IMAGES 1)
endif()

# The expectations as a JS object literal: {"SEL": N, ...}.
set(expect_js "")
foreach(entry IN LISTS EXPECT)
  string(FIND "${entry}" "=" eq REVERSE)
  string(SUBSTRING "${entry}" 0 ${eq} selector)
  math(EXPR after "${eq} + 1")
  string(SUBSTRING "${entry}" ${after} -1 count)
  string(REPLACE "\"" "\\\"" selector_js "${selector}")
  string(APPEND expect_js "\"${selector_js}\":${count},")
endforeach()

# A CMake string as a JavaScript string literal.
function(js_string out text)
  string(REPLACE "\\" "\\\\" text "${text}")
  string(REPLACE "\"" "\\\"" text "${text}")
  set(${out} "\"${text}\"" PARENT_SCOPE)
endfunction()
set(no_overlap_js "")
foreach(selector IN LISTS NO_OVERLAP)
  js_string(selector_js "${selector}")
  string(APPEND no_overlap_js "${selector_js},")
endforeach()
set(forbid_js "")
foreach(entry IN LISTS FORBID_TEXT)
  string(FIND "${entry}" "=" eq)
  string(SUBSTRING "${entry}" 0 ${eq} selector)
  math(EXPR after "${eq} + 1")
  string(SUBSTRING "${entry}" ${after} -1 regex)
  js_string(selector_js "${selector}")
  js_string(regex_js "${regex}")
  string(APPEND forbid_js "[${selector_js},${regex_js}],")
endforeach()

set(probe [=[
<script>
window.addEventListener('load', function () {
  var expect = {@expect_js@};
  var noOverlap = [@no_overlap_js@], forbid = [@forbid_js@];
  var out = {images: [], counts: {}, flip: null, overlaps: [], forbidden: []};
  document.querySelectorAll('img').forEach(function (i) {
    out.images.push({id: i.id || i.alt, complete: i.complete, width: i.naturalWidth});
  });
  for (var sel in expect) {
    var n = 0;
    if (sel.indexOf('points ') === 0) {
      document.querySelectorAll(sel.substring(7)).forEach(function (p) { n += p.points.numberOfItems; });
    } else {
      n = document.querySelectorAll(sel).length;
    }
    out.counts[sel] = n;
  }
  noOverlap.forEach(function (sel) {
    var els = Array.prototype.slice.call(document.querySelectorAll(sel));
    var boxes = els.map(function (e) { return e.getBoundingClientRect(); });
    var pairs = [];
    for (var i = 0; i < els.length; ++i) {
      for (var j = i + 1; j < els.length; ++j) {
        var a = boxes[i], b = boxes[j], slack = 0.5;  // touching edges are not an overlap
        if (a.left < b.right - slack && b.left < a.right - slack && a.top < b.bottom - slack && b.top < a.bottom - slack) {
          pairs.push('"' + els[i].textContent + '" and "' + els[j].textContent + '"');
        }
      }
    }
    out.overlaps.push({selector: sel, count: els.length, pairs: pairs.join(', ')});
  });
  forbid.forEach(function (rule) {
    var els = document.querySelectorAll(rule[0]), pattern = new RegExp(rule[1]), bad = [];
    els.forEach(function (e) { if (pattern.test(e.textContent)) bad.push('"' + e.textContent + '"'); });
    out.forbidden.push({selector: rule[0], regex: rule[1], count: els.length, matches: bad.join(', ')});
  });
  var toggle = document.getElementById('flip-toggle');
  if (toggle) {
    var view = document.getElementById('flip-view');
    var ref = document.getElementById('golden-reference'), test = document.getElementById('frame');
    // By what the view shows, not only by its source: a test frame identical to its reference has
    // the same data URI.
    var shows = function (what, img) { return view.dataset.showing === what && view.src === img.src; };
    var before = shows('reference', ref);
    toggle.click();
    var after = shows('test', test);
    toggle.click();
    out.flip = {startsOnReference: before, flipsToTest: after, backToReference: shows('reference', ref)};
  }
  var pre = document.createElement('pre');
  pre.id = 'fgb-probe';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script>
]=])
string(CONFIGURE "${probe}" probe @ONLY)
file(READ "${PAGE}" html)
string(FIND "${html}" "</body>" body_end REVERSE)
if(body_end LESS 0)
  message(FATAL_ERROR "browser-check: ${PAGE} has no </body>")
endif()
string(SUBSTRING "${html}" 0 ${body_end} head)
string(SUBSTRING "${html}" ${body_end} -1 tail)
set(probe_page "${PAGE}.probe.html")
file(WRITE "${probe_page}" "${head}${probe}${tail}")

get_filename_component(page_dir "${PAGE}" DIRECTORY)
set(profile "${page_dir}/.chromium-profile")
set(chromium_args --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir=${profile}
                  --virtual-time-budget=10000)
execute_process(COMMAND ${CHROMIUM} ${chromium_args} --dump-dom "file://${probe_page}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE dom ERROR_VARIABLE chromium_err TIMEOUT 120)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "browser-check: chromium --dump-dom ${probe_page} failed (${rc}): ${chromium_err}")
endif()
if(NOT dom MATCHES "<pre id=\"fgb-probe\">([^<]*)</pre>")
  message(FATAL_ERROR "browser-check: the probe did not run in ${probe_page} (no #fgb-probe in the DOM)")
endif()
set(json "${CMAKE_MATCH_1}")
string(REPLACE "&lt;" "<" json "${json}")
string(REPLACE "&gt;" ">" json "${json}")
string(REPLACE "&amp;" "&" json "${json}")

set(failures "")
string(JSON image_count LENGTH "${json}" images)
if(image_count LESS MIN_IMAGES)
  string(APPEND failures "\n  ${image_count} image(s), expected at least ${MIN_IMAGES}")
endif()
if(image_count GREATER 0)
  math(EXPR last "${image_count} - 1")
  foreach(i RANGE ${last})
    string(JSON id GET "${json}" images ${i} id)
    string(JSON complete GET "${json}" images ${i} complete)
    string(JSON width GET "${json}" images ${i} width)
    if(NOT complete OR width EQUAL 0)
      string(APPEND failures "\n  image '${id}' is broken (complete ${complete}, naturalWidth ${width})")
    else()
      message(STATUS "image '${id}': ${width} px wide")
    endif()
  endforeach()
endif()
foreach(entry IN LISTS EXPECT)
  string(FIND "${entry}" "=" eq REVERSE)
  string(SUBSTRING "${entry}" 0 ${eq} selector)
  math(EXPR after "${eq} + 1")
  string(SUBSTRING "${entry}" ${after} -1 expected)
  string(JSON got GET "${json}" counts "${selector}")
  if(NOT got EQUAL expected)
    string(APPEND failures "\n  '${selector}': ${got} in the rendered page, expected ${expected}")
  else()
    message(STATUS "'${selector}': ${got}")
  endif()
endforeach()
string(JSON overlap_count LENGTH "${json}" overlaps)
if(overlap_count GREATER 0)
  math(EXPR last "${overlap_count} - 1")
  foreach(i RANGE ${last})
    string(JSON selector GET "${json}" overlaps ${i} selector)
    string(JSON count GET "${json}" overlaps ${i} count)
    string(JSON pairs GET "${json}" overlaps ${i} pairs)
    if(count LESS 2)
      string(APPEND failures "\n  '${selector}': ${count} element(s), too few to check for overlaps")
    elseif(NOT pairs STREQUAL "")
      string(APPEND failures "\n  '${selector}' overlap: ${pairs}")
    else()
      message(STATUS "'${selector}': ${count} elements, none overlapping")
    endif()
  endforeach()
endif()
string(JSON forbid_count LENGTH "${json}" forbidden)
if(forbid_count GREATER 0)
  math(EXPR last "${forbid_count} - 1")
  foreach(i RANGE ${last})
    string(JSON selector GET "${json}" forbidden ${i} selector)
    string(JSON regex GET "${json}" forbidden ${i} regex)
    string(JSON count GET "${json}" forbidden ${i} count)
    string(JSON matches GET "${json}" forbidden ${i} matches)
    if(count EQUAL 0)
      string(APPEND failures "\n  '${selector}': no element, so nothing to check against /${regex}/")
    elseif(NOT matches STREQUAL "")
      string(APPEND failures "\n  '${selector}' text matching /${regex}/: ${matches}")
    else()
      message(STATUS "'${selector}': ${count} elements, none matching /${regex}/")
    endif()
  endforeach()
endif()
string(JSON flip_type TYPE "${json}" flip)
if(flip_type STREQUAL "OBJECT")
  foreach(key startsOnReference flipsToTest backToReference)
    string(JSON ok GET "${json}" flip ${key})
    if(NOT ok)
      string(APPEND failures "\n  flip toggle: ${key} is false")
    endif()
  endforeach()
  message(STATUS "flip toggle: reference -> test -> reference")
endif()

# A screenshot of the page as it is, for a person to look at.
set(screenshot "${PAGE}.png")
file(REMOVE "${screenshot}")
execute_process(COMMAND ${CHROMIUM} ${chromium_args} --window-size=1280,2600 --screenshot=${screenshot} "file://${PAGE}"
                RESULT_VARIABLE rc ERROR_VARIABLE chromium_err TIMEOUT 120)
if(NOT rc STREQUAL "0" OR NOT EXISTS "${screenshot}")
  string(APPEND failures "\n  no screenshot (${rc}): ${chromium_err}")
else()
  message(STATUS "screenshot: ${screenshot}")
endif()
file(REMOVE_RECURSE "${profile}")

if(failures)
  message(FATAL_ERROR "browser-check ${PAGE}:${failures}")
endif()
message(STATUS "browser-check ${PAGE}: ${image_count} image(s) loaded, every expected count found")
