#include "core/render/row_renderer.h"

#include "core/render/strategy_table.h"

namespace penumbra {

RowRenderer makeRowRenderer(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  return strategyRow(d.strategy).makeRows(job, d);
}

}  // namespace penumbra
