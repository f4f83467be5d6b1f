/* pitheorem docs: a display equation wider than its column is set smaller until it fits, down
   to MIN_SCALE of its size, so that a phone shows it whole rather than behind a scrollbar.
   An equation that would need more than that is broken into lines in its source instead
   (docs/check_pages.py reports any that still does not fit at 390 px). It runs once MathJax
   has typeset the page (the notebooks' outputs included), and again when the window's width
   changes. No network, no library: the page's own MathJax, nothing else. */
(function () {
  "use strict";
  var MIN_SCALE = 0.62;

  function fit() {
    var equations = document.querySelectorAll('mjx-container[display="true"]');
    for (var i = 0; i < equations.length; i++) {
      var eq = equations[i];
      // MathJax sets its own size on the container (to match the text): scale that, not 100 %
      if (eq.dataset.fitBase === undefined) {
        eq.dataset.fitBase = eq.style.fontSize || "";
      }
      var base = eq.dataset.fitBase;
      eq.style.fontSize = base;
      var column = eq.clientWidth;
      var needed = eq.scrollWidth;
      if (column > 0 && needed > column + 1) {
        var scale = Math.max(MIN_SCALE, (column - 2) / needed);
        var percent = base ? parseFloat(base) : 100;
        eq.style.fontSize = (percent * scale).toFixed(2) + "%";
      }
    }
  }

  var pending = null;
  function fitSoon() {
    if (pending !== null) {
      window.clearTimeout(pending);
    }
    pending = window.setTimeout(function () {
      pending = null;
      fit();
    }, 100);
  }

  function start() {
    var mj = window.MathJax;
    if (mj && mj.startup && mj.startup.promise) {
      mj.startup.promise.then(fit);
    } else {
      fit();
    }
    // the math fonts may arrive after the first typeset, and the column may settle later
    // (the theme's sidebars): measure again then, and whenever the column's width changes
    if (document.fonts && document.fonts.ready) {
      document.fonts.ready.then(fitSoon);
    }
    var column = document.querySelector("article") || document.body;
    var width = column.clientWidth;
    if (window.ResizeObserver) {
      new window.ResizeObserver(function () {
        if (column.clientWidth !== width) {
          width = column.clientWidth;
          fitSoon();
        }
      }).observe(column);
    }
    window.addEventListener("resize", fitSoon);
  }

  if (document.readyState === "complete") {
    start();
  } else {
    window.addEventListener("load", start);
  }
})();
