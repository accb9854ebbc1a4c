// Search over the papers' wording: the query is put in the same canonical form as the index
// (window.TRACKCERT_SEARCH.rules, the report's theory.report.search.RULES), then every entry
// whose words contain it at a word start, ending at a word end or a dot, is listed.
(function () {
  var data = window.TRACKCERT_SEARCH, form = document.getElementById("search");
  if (!data) { return; }
  var rules = data.rules.map(function (r) { return [new RegExp(r[0], "g"), r[1]]; });
  function canonical(text) {
    var out = text.toLowerCase();
    rules.forEach(function (r) { out = out.replace(r[0], r[1]); });
    return out.trim();
  }
  function matches(words, query) {
    var padded = " " + words + " ", at = padded.indexOf(" " + query);
    while (at >= 0) {
      var next = padded.charAt(at + query.length + 1);
      if (next === " " || next === ".") { return true; }
      at = padded.indexOf(" " + query, at + 1);
    }
    return false;
  }
  window.trackcertSearch = { canonical: canonical, matches: matches };
  if (!form) { return; }
  var root = form.getAttribute("data-root") || "";
  var list = document.getElementById("search-results"), count = document.getElementById("search-count");
  function run() {
    var query = canonical(form.elements.q.value);
    list.textContent = "";
    if (!query) { count.textContent = ""; return; }
    var found = data.entries.filter(function (e) { return matches(e.words, query); });
    count.textContent = found.length + " match" + (found.length === 1 ? "" : "es");
    found.slice(0, 200).forEach(function (e) {
      var item = document.createElement("li"), link = document.createElement("a");
      item.setAttribute("data-kind", e.kind);
      link.href = root + e.href;
      link.textContent = e.text;
      item.appendChild(link);
      item.appendChild(document.createTextNode(" — " + e.detail));
      list.appendChild(item);
    });
  }
  var preset = /(?:^#|&)q=([^&]*)/.exec(location.hash);
  if (preset) { form.elements.q.value = decodeURIComponent(preset[1]); }
  form.addEventListener("input", run);
  run();
})();
