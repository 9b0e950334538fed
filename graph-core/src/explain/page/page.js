// Click, Enter or Space on a name pins its details open (its button's aria-expanded);
// Escape closes every pinned one. Hover and focus show them without this script.
for (const button of document.querySelectorAll(".has-tip > button")) {
  button.addEventListener("click", () => {
    const open = button.getAttribute("aria-expanded") === "true";
    button.setAttribute("aria-expanded", String(!open));
  });
}
document.addEventListener("keydown", (event) => {
  if (event.key !== "Escape") return;
  for (const button of document.querySelectorAll('.has-tip > button[aria-expanded="true"]')) {
    button.setAttribute("aria-expanded", "false");
  }
});
