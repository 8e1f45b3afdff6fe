-- Run by tests/test_server.py in a headless Neovim whose init.lua is the documented set-up
-- (docs/editors.md): once the wanted diagnostic is in the first buffer (and a few seconds
-- more, for any later publisher), write as JSON what Neovim holds: each buffer's name,
-- attached clients and vim.diagnostic entries, and the urdf-lint server processes Neovim
-- started (its children running `urdf_lint server`).
local out = os.getenv("URDF_LINT_NVIM_OUT")
local want = os.getenv("URDF_LINT_NVIM_WANT")
local first = vim.api.nvim_list_bufs()[1]
local function has_wanted()
  for _, d in ipairs(vim.diagnostic.get(first)) do
    local lsp = (d.user_data or {}).lsp or {}
    if (d.code or lsp.code) == want then
      return true
    end
  end
  return false
end
vim.wait(90000, has_wanted, 200)
vim.wait(5000, function() return false end, 200)
local bufs = {}
for _, b in ipairs(vim.api.nvim_list_bufs()) do
  local diags = {}
  for _, d in ipairs(vim.diagnostic.get(b)) do
    local lsp = (d.user_data or {}).lsp or {}
    table.insert(diags, { lnum = d.lnum, col = d.col, message = d.message,
      code = d.code or lsp.code, namespace = d.namespace })
  end
  local ids = {}
  for id, _ in pairs(vim.lsp.buf_get_clients(b)) do
    table.insert(ids, id)
  end
  table.insert(bufs, { name = vim.api.nvim_buf_get_name(b), clients = ids, diagnostics = diags })
end
local procs = vim.fn.systemlist({ "ps", "-o", "pid=,args=", "--ppid", tostring(vim.fn.getpid()) })
local servers = {}
for _, line in ipairs(procs) do
  if line:find("urdf_lint server", 1, true) then
    table.insert(servers, line)
  end
end
local f = io.open(out, "w")
f:write(vim.fn.json_encode({ buffers = bufs, servers = servers,
  clients = #vim.lsp.get_active_clients() }))
f:close()
vim.cmd("qall!")
