/* The book's MathJax: configure MathJax 3 and load its TeX-to-SVG component from the copy beside this file
   (assets/mathjax/, from the django-static-mathjax package). SVG output draws the glyphs as paths held in the
   script, so no font file is fetched, and the page needs no network. The delimiters are those of Jupyter:
   $...$ and \(...\) inline, $$...$$ and \[...\] displayed; \$ is a dollar sign. Code (<pre>, <code>) is
   never typeset (MathJax's default skipHtmlTags). */
window.MathJax = {
  tex: {
    inlineMath: [["$", "$"], ["\\(", "\\)"]],
    displayMath: [["$$", "$$"], ["\\[", "\\]"]],
    processEscapes: true,
    processEnvironments: true,
    tags: "ams",
  },
  svg: {fontCache: "global"},
  options: {ignoreHtmlClass: "tex2jax_ignore", processHtmlClass: "tex2jax_process"},
};
(function () {
  var script = document.createElement("script");
  script.src = new URL("mathjax/tex-svg.js", document.currentScript.src).href;
  script.async = true;
  document.head.appendChild(script);
})();
