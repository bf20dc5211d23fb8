!> The contact package's deck group &contact (one interface per group), its
!> keys declared once in CONTACT_KEYS (core_keys) next to its reader.
!> io_deck has checked the key names and value types and hands the reader the
!> group's text; the reader does the namelist read and the checks of the values.
module contact_deck
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_lower
  use core_keys, only: key_t
  use mesh_global, only: NAME_LEN
  use contact_enforce, only: contact_spec_t, SURFACE_LEN
  implicit none
  private
  public :: read_contact

  !> &contact: one interface between face sets.
  type(key_t), parameter, public :: CONTACT_KEYS(18) = [ &
      key_t("name", "c", "''", "", &
      "label of the interface's history columns"), &
      key_t("surface_a", "c", "required", "", &
      "face set(s) of one side, separated by blanks or commas, or blocks ('block:NAME')"), &
      key_t("surface_b", "c", "surface_a", "", &
      "face set(s) of the other side (omitted: self-contact)"), &
      key_t("method", "c", "required", "", &
      "'dam' (discrete accurate matching) or 'dlm' (discrete Lagrangian multiplier)"), &
      key_t("master", "c", "'b'", "", &
      "DAM: the master side, 'a' or 'b' (not for DLM)"), &
      key_t("capture", "r", "0", "length", &
      "largest open gap treated as contact (0 = automatic)"), &
      key_t("penetration_warning", "r", "-", "", &
      "removed: refused with a message naming penetration_tolerance"), &
      key_t("search_margin", "r", "0", "length", &
      "territory margin of the global search (0 = half the median segment size)"), &
      key_t("search_every", "i", "0", "cycles", &
      "cycles between global searches (0 = automatic from the margin and the largest speed)"), &
      key_t("form", "c", "'velocity'", "", &
      "DLM: 'velocity', 'combined' or 'coordinate'"), &
      key_t("sweeps", "i", "1", "", &
      "DLM, velocity form: Gauss-Seidel sweeps of the facet-pair forces"), &
      key_t("recovery", "r", "0.2", "", &
      "DLM, velocity form: fraction (0 to 0.5) of the excess penetration removed per step"), &
      key_t("normal", "c", "'master'", "", &
      "DAM: the contact normal of a slave node, 'master' or 'slave'"), &
      key_t("penetration_tolerance", "r", "0", "length", &
      "penetration the audit accepts at a node (0 = automatic)"), &
      key_t("on_penetration", "c", "'warn'", "", &
      "what the audit does with nodes deeper than the tolerance: 'warn' or 'stop'"), &
      key_t("initial_penetration", "c", "'error'", "", &
      "penetration at set-up beyond the tolerance: 'error', 'adjust' or 'ignore'"), &
      key_t("friction", "r", "0", "", &
      "Coulomb friction coefficient mu >= 0 (finite), both methods"), &
      key_t("symmetric", "l", ".true.", "", &
      "DAM: a second pass with master and slave swapped (self-contact: the other side)")]

contains

  !> The index-th &contact into pair (its defaults are pair's on entry).
  subroutine read_contact(sect, index, pair, status, symmetric_given)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    integer, intent(in) :: index
    type(contact_spec_t), intent(inout) :: pair
    type(status_t), intent(inout) :: status
    logical, intent(in) :: symmetric_given !< the deck sets symmetric
    character(len=NAME_LEN) :: name, master
    character(len=SURFACE_LEN) :: surface_a, surface_b
    character(len=16) :: method, form, normal, on_penetration, initial_penetration
    real(rk) :: capture, penetration_warning, search_margin, recovery, penetration_tolerance
    real(rk) :: friction
    logical :: symmetric
    integer :: search_every, sweeps, ios
    character(len=256) :: msg
    character(len=16) :: where
    namelist /contact/ name, surface_a, surface_b, method, master, capture, &
        penetration_warning, search_margin, search_every, form, sweeps, recovery, normal, &
        penetration_tolerance, on_penetration, initial_penetration, friction, symmetric

    write(where, '(a,i0,a)') '&contact(', index, ')'
    name = ''
    surface_a = ''
    surface_b = ''
    method = ''
    master = ''
    capture = pair%capture
    penetration_warning = -1.0_rk
    penetration_tolerance = pair%penetration_tolerance
    on_penetration = pair%on_penetration
    initial_penetration = pair%initial_penetration
    search_margin = pair%search_margin
    search_every = pair%search_every
    sweeps = pair%sweeps
    recovery = pair%recovery
    friction = pair%friction
    symmetric = pair%symmetric
    form = ''
    normal = ''
    read(sect, nml=contact, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    pair%name = name
    if (len_trim(surface_a) == 0) call status%add(trim(where)//': surface_a: required '// &
        '(a face set)')
    pair%surface_a = surface_a
    pair%surface_b = surface_b
    if (len_trim(surface_b) == 0) pair%surface_b = surface_a
    select case (to_lower(method))
    case ('dam', 'dlm')
      pair%method = to_lower(method)
    case ('')
      call status%add(trim(where)//': method: required (valid: dam, dlm)')
    case default
      call status%add(trim(where)//': method: '''//trim(method)//''' is not a contact '// &
          'method (valid: dam, dlm)')
    end select
    select case (to_lower(master))
    case ('')
      pair%master = 'b'
    case ('a', 'b')
      pair%master = to_lower(master)
      if (to_lower(method) == 'dlm') call status%add(trim(where)//': master: DLM is '// &
          'symmetric and has no master side')
    case default
      call status%add(trim(where)//': master: must be ''a'' or ''b'' (the master side for DAM)')
    end select
    select case (to_lower(form))
    case ('')
    case ('coordinate', 'velocity', 'combined')
      pair%form = to_lower(form)
      if (to_lower(method) == 'dam') call status%add(trim(where)//': form: only DLM has '// &
          'forms (coordinate, velocity, combined)')
    case default
      call status%add(trim(where)//': form: '''//trim(form)//''' is not a DLM form (valid: '// &
          'coordinate, velocity, combined)')
    end select
    select case (to_lower(normal))
    case ('')
    case ('master', 'slave')
      pair%normal = to_lower(normal)
      if (to_lower(method) == 'dlm') call status%add(trim(where)//': normal: only for DAM '// &
          '(DLM uses the common normal of each segment pair)')
    case default
      call status%add(trim(where)//': normal: '''//trim(normal)//''' is not a DAM normal '// &
          '(valid: master, slave)')
    end select
    if (.not. (capture >= 0.0_rk)) call status%add(trim(where)//': capture: must be >= 0')
    if (penetration_warning /= -1.0_rk) call status%add(trim(where)// &
        ': penetration_warning: replaced by penetration_tolerance (a length; default the '// &
        'larger of 5% of the smaller adjacent segment and the faceting sagitta)')
    if (.not. (penetration_tolerance >= 0.0_rk)) call status%add(trim(where)// &
        ': penetration_tolerance: must be >= 0 (a length; 0 = automatic)')
    select case (to_lower(on_penetration))
    case ('warn', 'stop')
      pair%on_penetration = to_lower(on_penetration)
    case default
      call status%add(trim(where)//': on_penetration: '''//trim(on_penetration)// &
          ''' is not a choice (valid: warn, stop)')
    end select
    select case (to_lower(initial_penetration))
    case ('error', 'adjust', 'ignore')
      pair%initial_penetration = to_lower(initial_penetration)
    case default
      call status%add(trim(where)//': initial_penetration: '''//trim(initial_penetration)// &
          ''' is not a choice (valid: error, adjust, ignore)')
    end select
    if (.not. (search_margin >= 0.0_rk)) call status%add(trim(where)// &
        ': search_margin: must be >= 0 (0 = automatic)')
    if (search_every < 0) call status%add(trim(where)//': search_every: must be >= 0 '// &
        '(0 = automatic)')
    pair%capture = capture
    pair%penetration_tolerance = penetration_tolerance
    pair%search_margin = search_margin
    pair%search_every = search_every
    if (sweeps < 1) call status%add(trim(where)//': sweeps: must be >= 1')
    pair%sweeps = sweeps
    if (recovery /= pair%recovery) then
      if (.not. (recovery >= 0.0_rk .and. recovery <= 0.5_rk)) call status%add(trim(where)// &
          ': recovery: must be in [0, 0.5] (fraction of the penetration removed per step)')
      if (to_lower(method) == 'dam' .or. .not. (form == '' .or. to_lower(form) == 'velocity')) &
          call status%add(trim(where)//': recovery: only for the DLM velocity form')
    end if
    pair%recovery = recovery
    if (.not. (friction >= 0.0_rk)) call status%add(trim(where)// &
        ': friction: must be >= 0 (the Coulomb coefficient; 0 = frictionless)')
    pair%friction = friction
    if (symmetric_given .and. to_lower(method) == 'dlm') call status%add(trim(where)// &
        ': symmetric: only for DAM (DLM is symmetric: every facet pair acts on both sides)')
    pair%symmetric = symmetric .and. to_lower(method) == 'dam'
  end subroutine read_contact

end module contact_deck
