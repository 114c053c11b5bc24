-- Neovim's own client (0.7 or later), headless, against `rayrepl lsp`:
-- opens each file of $RAYREPL_FILES (one per line), waits for its
-- diagnostics, asks what $RAYREPL_ASK lists, and writes what Neovim
-- received as JSON to $RAYREPL_ANSWERS. tests/lsp/test_neovim.py runs it.
local function main()
local files = vim.split(os.getenv("RAYREPL_FILES"), "\n", { trimempty = true })
local answers = {}
local published = {}
local handlers = {
  ["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
    vim.lsp.diagnostic.on_publish_diagnostics(err, result, ctx, config)
    published[result.uri] = result.diagnostics
  end,
}
local client = vim.lsp.start_client({
  name = "rayrepl",
  cmd = { os.getenv("RAYREPL"), "lsp" },
  root_dir = vim.fn.getcwd(),
  handlers = handlers,
})
local asks = vim.json.decode(os.getenv("RAYREPL_ASK") or "{}")
for _, file in ipairs(files) do
  vim.cmd("edit " .. vim.fn.fnameescape(file))
  local buffer = vim.api.nvim_get_current_buf()
  local uri = vim.uri_from_bufnr(buffer)
  vim.lsp.buf_attach_client(buffer, client)
  vim.wait(10000, function() return published[uri] end, 10)
  -- What Neovim received, and how many it shows.
  local found = {}
  for _, diagnostic in ipairs(published[uri] or {}) do
    table.insert(found, { code = diagnostic.code, line = diagnostic.range.start.line, character = diagnostic.range.start.character })
  end
  local shown = #vim.diagnostic.get(buffer)
  local asked = {}
  for _, ask in ipairs(asks[vim.fn.fnamemodify(file, ":t")] or {}) do
    local params = { textDocument = { uri = uri }, position = ask.position }
    for key, value in pairs(ask.more or {}) do params[key] = value end
    local replies = vim.lsp.buf_request_sync(buffer, ask.method, params, 5000) or {}
    local reply = replies[client] or {}
    table.insert(asked, { method = ask.method, result = reply.result, error = reply.err })
  end
  answers[vim.fn.fnamemodify(file, ":t")] = { diagnostics = found, shown = shown, asked = asked, published = published[uri] ~= nil }
end
local out = io.open(os.getenv("RAYREPL_ANSWERS"), "w")
out:write(vim.json.encode(answers))
out:close()
vim.lsp.stop_client(client)
vim.wait(5000, function() return vim.lsp.client_is_stopped(client) end, 10)
end

-- Any error ends Neovim with a failure, rather than leave it waiting.
local ok, error = pcall(main)
if not ok then
  io.stderr:write(tostring(error) .. "\n")
  vim.cmd("cquit 1")
end
vim.cmd("qall!")
