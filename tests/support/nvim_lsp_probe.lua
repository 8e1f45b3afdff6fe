-- Run by tests/test_server.py in a headless Neovim: start urdf-lint server with Neovim's own
-- LSP client for the current buffer, and once a diagnostic with the wanted code arrived, write
-- what vim.diagnostic holds for the buffer (Neovim's view, not the server's message) as JSON.
local out = os.getenv("URDF_LINT_NVIM_OUT")
local want = os.getenv("URDF_LINT_NVIM_WANT")
local bufnr = vim.api.nvim_get_current_buf()
local function dump()
  local got = {}
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    local lsp = (d.user_data or {}).lsp or {}
    table.insert(got, { lnum = d.lnum, col = d.col, end_lnum = d.end_lnum, end_col = d.end_col,
      message = d.message, severity = d.severity, source = d.source,
      code = d.code or lsp.code })
  end
  local f = io.open(out, "w")
  f:write(vim.fn.json_encode(got))
  f:close()
end
vim.g.urdf_lint_cmd = { os.getenv("URDF_LINT_PY"), "-m", "urdf_lint", "server" }
vim.g.urdf_lint_handlers = {
  ["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
    vim.lsp.diagnostic.on_publish_diagnostics(err, result, ctx, config)
    for _, d in ipairs(result.diagnostics) do
      if d.code == want and result.uri == vim.uri_from_bufnr(bufnr) then
        dump()
        vim.cmd("qall!")
      end
    end
  end,
}
local plugin = dofile(os.getenv("URDF_LINT_NVIM_PLUGIN"))
plugin.start(bufnr)
vim.defer_fn(function() vim.cmd("qall!") end, 90000)
