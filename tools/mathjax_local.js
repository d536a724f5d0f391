/* The book's MathJax settings, loaded after the combined TeX-AMS-MML_HTMLorMML-full configuration: the
   jupyter-server-mathjax bundle ships the STIX-Web fonts only (not MathJax's default TeX fonts, nor image
   fonts), so the HTML-CSS output is told to use them and not to look for the others. Its blank reference
   font (used to tell when a web font has loaded) is declared as url('about:blank'), which a page opened from
   file:// may not fetch (a console error in Chromium); local() names it without any fetch. */
MathJax.Hub.Config({
  "HTML-CSS": {
    availableFonts: [],
    preferredFont: null,
    webFont: "STIX-Web",
    imageFont: null,
    styles: {"@font-face": {"font-family": "MathJax_Blank", src: "local('MathJax_Blank')"}},
  },
});
MathJax.Ajax.loadComplete("[MathJax]/config/local/ssi.js");
