// "New patient": the form's files go to POST /api/patients (docs/protocol.md) as multipart form
// data, with the upload's progress shown; the server checks and imports them, and the new case
// joins the list and opens. Every refusal names the file and what is wrong.
"use strict";

function importStatus(text, kind = "info") {
  const line = document.createElement("div");
  line.className = kind;
  line.textContent = text;
  $("import-status").replaceChildren(line);
}

function patientForm() {
  const form = $("patient-form");
  const data = new FormData(form);
  const cuts = data.getAll("cut");
  data.delete("cut");
  data.set("cuts", cuts.join(","));
  // Fields left empty are not sent: a label map's numbers only with a label map.
  for (const key of ["tissue_labels", "skull_labels", "mandible_labels"]) if (!data.get(key)) data.delete(key);
  return data;
}

function submitPatient(event) {
  event.preventDefault();
  const data = patientForm();
  const id = data.get("id");
  const xhr = new XMLHttpRequest();
  xhr.open("POST", "/api/patients");
  if (token()) xhr.setRequestHeader("Authorization", `Bearer ${token()}`);
  const progress = $("import-progress");
  progress.hidden = false;
  progress.value = 0;
  $("import-patient").disabled = true;
  importStatus("uploading…");
  xhr.upload.onprogress = (e) => {
    if (!e.lengthComputable) return;
    progress.value = 0.9 * (e.loaded / e.total);  // the last tenth: the server's checks
    if (e.loaded === e.total) importStatus("checking the surfaces and writing the case…");
  };
  xhr.onerror = () => finishImport(null, "the upload failed: is the server running?");
  xhr.onload = () => {
    let reply = null;
    try { reply = JSON.parse(xhr.responseText); } catch (e) { reply = { message: xhr.statusText }; }
    if (xhr.status === 201) finishImport(reply, null);
    else finishImport(null, `${reply.message || xhr.statusText}${reply.field ? ` (field ${reply.field})` : ""}`);
  };
  xhr.send(data);
  say(`uploading patient ${id}…`);
}

function finishImport(reply, error) {
  $("import-patient").disabled = false;
  $("import-progress").value = error ? 0 : 1;
  if (error) {
    importStatus(`not imported: ${error}`, "error");
    return say(`import refused: ${error}`, "error");
  }
  const c = reply.case;
  const warnings = reply.warnings.length ? ` Warnings: ${reply.warnings.join("; ")}.` : "";
  const built = reply.built && reply.built.length ? ` Built: ${reply.built.join("; ")}.` : "";
  importStatus(`imported ${c.name} (${c.id}); frame ${reply.frame}${reply.scale !== 1 ? `, scaled ×${reply.scale}` : ""}.${built}${warnings}`);
  say(`patient ${c.id} imported; opening it`);
  state.openAfterList = c.id;
  send({ type: "list_cases" });
}

$("patient-form").addEventListener("submit", submitPatient);
