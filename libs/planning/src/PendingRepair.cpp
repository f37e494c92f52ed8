/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/planning/PendingRepair.h>

#include "FieldRepair.h"

namespace semnav
{
PendingRepair::PendingRepair() = default;
PendingRepair::~PendingRepair() = default;
PendingRepair::PendingRepair(PendingRepair&&) noexcept = default;
PendingRepair& PendingRepair::operator=(PendingRepair&&) noexcept = default;

bool PendingRepair::empty() const
{
	return !m_repairer;
}

double PendingRepair::settledCost() const
{
	return m_repairer ? m_repairer->settledCost() : detail::kInf;
}

CellIndex PendingRepair::start() const
{
	return m_repairer ? m_repairer->start() : CellIndex{0, 0};
}

void PendingRepair::clear()
{
	m_repairer.reset();
	m_u = nullptr;
	m_goals = nullptr;
	m_workLimit = 0;
}

}  // namespace semnav
